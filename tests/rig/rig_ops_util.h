/*
 * rig_ops_util.h - the lab as an operator runs it (issue 29): strayrigd
 * and `stray` run as programs (STRAY_BUILD/bin/strayrigd, STRAY_BIN), so
 * a test fails on a build without the fix.  Include after cmocka.h and
 * rig_test_util.h.
 */
#ifndef RIG_OPS_UTIL_H
#define RIG_OPS_UTIL_H

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* Run cmd through the shell; exit status, stdout+stderr into out. */
static inline int run_out(const char *cmd, const char *dir, char *out, size_t size)
{
	char full[4096], path[700];
	FILE *f;
	size_t n = 0;
	int status;

	snprintf(path, sizeof(path), "%s/out.txt", dir);
	snprintf(full, sizeof(full), "%s >'%s' 2>&1", cmd, path);
	status = system(full);
	f = fopen(path, "r");
	if (f) {
		n = fread(out, 1, size - 1, f);
		fclose(f);
	}
	out[n] = '\0';
	return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static inline const char *rigd(void)
{
	static char bin[600];
	const char *b = getenv("STRAY_BUILD");

	snprintf(bin, sizeof(bin), "%s/bin/strayrigd", b ? b : "build");
	return bin;
}

static inline const char *stray(void)
{
	const char *s = getenv("STRAY_BIN");

	return s ? s : "build/bin/stray";
}

static inline void put(const char *dir, const char *name, const char *text)
{
	char path[700];
	FILE *f;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

/* The daemon serve() started last: killed at exit if a failed test
 * left it running. */
static pid_t served_pid;
static int served_atexit;

static inline void kill_served(void)
{
	if (served_pid > 0)
		kill(served_pid, SIGKILL);
}

/* strayrigd serving a socket in the background; its pid. */
static inline pid_t serve(const char *dir, const char *conf, const char *sock)
{
	char path[700];
	struct stat st;
	pid_t pid = fork();
	int i;

	assert_true(pid >= 0);
	if (pid == 0) {
		snprintf(path, sizeof(path), "%s/served.err", dir);
		/* stdout too: a pipe held open by a daemon left behind by a
		 * failed test would hang whoever reads the test's output */
		if (!freopen(path, "w", stderr) ||
		    !freopen("/dev/null", "w", stdout))
			_exit(126);
		execl(rigd(), rigd(), "--config", conf, "--socket", sock,
		      (char *)NULL);
		_exit(127);
	}
	served_pid = pid;
	if (!served_atexit)
		served_atexit = atexit(kill_served) == 0;
	for (i = 0; i < 500 && stat(sock, &st) != 0; i++) {
		struct timespec ts = { 0, 10000000 };

		nanosleep(&ts, NULL);
	}
	return pid;
}

static inline void stop(pid_t pid)
{
	int status;

	kill(pid, SIGTERM);
	waitpid(pid, &status, 0);
	if (pid == served_pid)
		served_pid = 0;
}

/* A whole small file into buf ("" if missing). */
static inline void slurp(const char *path, char *buf, size_t size)
{
	FILE *f = fopen(path, "r");
	size_t n = f ? fread(buf, 1, size - 1, f) : 0;

	buf[n] = '\0';
	if (f)
		fclose(f);
}

/* Sleep ms milliseconds. */
static inline void nap(long ms)
{
	struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };

	nanosleep(&ts, NULL);
}

/* `stray rig --socket SOCK ARGS`: exit status, output into out. */
static inline int rig_cli(const char *dir, const char *sock, const char *args,
			  char *out, size_t size)
{
	char cmd[2048];

	snprintf(cmd, sizeof(cmd), "%s rig --socket '%s' %s", stray(), sock,
		 args);
	return run_out(cmd, dir, out, size);
}

/* Poll `stray rig --json status` until its state is want (or ~10 s). */
static inline int wait_for_state(const char *dir, const char *sock,
				 const char *want, char *out, size_t size)
{
	char pat[64];
	int i;

	snprintf(pat, sizeof(pat), "\"state\":\"%s\"", want);
	for (i = 0; i < 500; i++) {
		rig_cli(dir, sock, "--json status", out, size);
		if (strstr(out, pat))
			return 1;
		nap(20);
	}
	return 0;
}

#endif /* RIG_OPS_UTIL_H */
