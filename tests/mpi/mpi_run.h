/*
 * mpi_run.h - what the mpirun tests share: shell commands with a hard
 * timeout (a hang fails the test instead of stalling CI), a scratch
 * folder, byte comparison of files, and the pid of one rank of a job
 * started by this test (found by a marker in its environment).
 */
#ifndef STRAY_TESTS_MPI_RUN_H
#define STRAY_TESTS_MPI_RUN_H

#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

static char scratch[64];
static char marker[64];

/* Env for Open MPI as root (CI), a marker for rank_pid, a scratch dir. */
static void mpi_test_setup(void)
{
	setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
	setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
	snprintf(marker, sizeof(marker), "%ld", (long)getpid());
	setenv("STRAY_MPI_TEST_MARK", marker, 1);
	snprintf(scratch, sizeof(scratch), "/tmp/stray_mpi_XXXXXX");
	assert_non_null(mkdtemp(scratch));
}

static const char *bin(const char *name)
{
	static char path[2][512];
	static int k;
	const char *b = getenv("STRAY_BUILD") ? getenv("STRAY_BUILD") : "build";
	char cwd[256];

	k ^= 1;
	/* the commands run in the scratch folder: an absolute path */
	assert_non_null(getcwd(cwd, sizeof(cwd)));
	snprintf(path[k], sizeof(path[k]), "%s%s%s/bin/%s", b[0] == '/' ? "" :
		 cwd, b[0] == '/' ? "" : "/", b, name);
	return path[k];
}

/* Run a shell command (in the scratch folder); its exit status. */
static int shell(const char *fmt, ...)
{
	char cmd[4096], full[4300];
	va_list ap;
	int st;

	va_start(ap, fmt);
	vsnprintf(cmd, sizeof(cmd), fmt, ap);
	va_end(ap);
	snprintf(full, sizeof(full), "cd %s && %s", scratch, cmd);
	st = system(full);
	return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* The files' bytes are equal (both exist), but for the provenance line
 * "# command: ..." of a curve, which names the program that ran it
 * (stray or stray-mpi, mpirun's ranks): every other byte is compared. */
static inline int same_bytes(const char *a, const char *b)
{
	return shell("test -s %s && test -s %s && "
		     "grep -v '^# command: ' %s > %s.cmp; "
		     "grep -v '^# command: ' %s > %s.cmp; cmp -s %s.cmp %s.cmp",
		     a, b, a, a, b, b, a, b) == 0;
}

static inline int file_has(const char *name, const char *text)
{
	return shell("grep -qF -- '%s' %s", text, name) == 0;
}

/* The pid of rank `rank` of a job this test started, or -1. */
static inline long rank_pid(int rank)
{
	char want_mark[96], want_rank[64], path[300], env[16384];
	DIR *d = opendir("/proc");
	struct dirent *e;
	long found = -1;

	snprintf(want_mark, sizeof(want_mark), "STRAY_MPI_TEST_MARK=%s", marker);
	snprintf(want_rank, sizeof(want_rank), "OMPI_COMM_WORLD_RANK=%d", rank);
	while (d && found < 0 && (e = readdir(d))) {
		FILE *f;
		size_t n, i;
		int m = 0, r = 0;

		if (e->d_name[0] < '1' || e->d_name[0] > '9')
			continue;
		snprintf(path, sizeof(path), "/proc/%s/environ", e->d_name);
		if (!(f = fopen(path, "rb")))
			continue;
		n = fread(env, 1, sizeof(env) - 1, f);
		fclose(f);
		env[n] = '\0';
		for (i = 0; i < n; i += strlen(env + i) + 1) {
			m |= strcmp(env + i, want_mark) == 0;
			r |= strcmp(env + i, want_rank) == 0;
		}
		if (m && r)
			found = atol(e->d_name);
	}
	if (d)
		closedir(d);
	return found;
}

/* Run a test group in a fresh scratch folder, removed when all pass. */
#define mpi_run_group(tests) mpi_run_group_n(#tests, tests, \
	sizeof(tests) / sizeof((tests)[0]))

static int mpi_run_group_n(const char *name, const struct CMUnitTest *tests,
			   size_t n)
{
	int rc;

	mpi_test_setup();
	rc = _cmocka_run_group_tests(name, tests, n, NULL, NULL);
	if (rc == 0)
		shell("cd / && rm -rf %s", scratch);
	return rc;
}

#endif /* STRAY_TESTS_MPI_RUN_H */
