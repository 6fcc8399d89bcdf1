/*
 * run_cli.h - run build/bin/stray as a user would (fork and exec, stdout
 * and stderr captured to files) for the CLI tests.
 */
#ifndef STRAY_TESTS_RUN_CLI_H
#define STRAY_TESTS_RUN_CLI_H

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

struct cli_run {
	int status;		/* exit status, or -1 when it did not exit */
	char out[1 << 16];
	char err[1 << 12];
	int err_lines;
};

static inline void slurp(const char *path, char *buf, size_t size)
{
	FILE *f = fopen(path, "rb");
	size_t n = f ? fread(buf, 1, size - 1, f) : 0;

	buf[n] = '\0';
	if (f)
		fclose(f);
}

/*
 * argv[0] is ignored (replaced by $STRAY_BIN); NULL-terminated.  limited:
 * a time limit (a hang is killed: status -1) and an address-space limit
 * (a 1 GB allocation fails instead of swapping), for the hostile files.
 */
static inline int run_cli(struct cli_run *r, char *const argv[], int limited)
{
	const char *bin = getenv("STRAY_BIN") ? getenv("STRAY_BIN")
					      : "build/bin/stray";
	char out[] = "/tmp/stray_out_XXXXXX", err[] = "/tmp/stray_err_XXXXXX";
	int fo = mkstemp(out), fe = mkstemp(err), st;
	pid_t pid = fork();
	const char *p;

	if (pid == 0) {
		struct rlimit rl = { 768L << 20, 768L << 20 };

		dup2(fo, 1);
		dup2(fe, 2);
		/* not under ASan: it reserves terabytes of address space */
		if (limited && !strstr(bin, "/asan/"))
			setrlimit(RLIMIT_AS, &rl);
		if (limited)
			alarm(20);	/* kept across execv */
		execv(bin, argv);
		_exit(127);
	}
	waitpid(pid, &st, 0);
	close(fo);
	close(fe);
	slurp(out, r->out, sizeof(r->out));
	slurp(err, r->err, sizeof(r->err));
	unlink(out);
	unlink(err);
	r->status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
	for (r->err_lines = 0, p = r->err; *p; p++)
		r->err_lines += *p == '\n';
	return r->status;
}

static inline int run_stray(struct cli_run *r, char *const argv[])
{
	return run_cli(r, argv, 0);
}

static inline int run_stray_limited(struct cli_run *r, char *const argv[])
{
	return run_cli(r, argv, 1);
}

#endif /* STRAY_TESTS_RUN_CLI_H */
