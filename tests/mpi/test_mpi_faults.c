/*
 * test_mpi_faults.c - a rank lost in the middle of an MPI sweep: stopped
 * (SIGSTOP) it is noticed by rank 0 after --task-timeout and reported in
 * one line; killed (SIGKILL) mpirun ends the job; neither hangs (every
 * command runs under timeout).  Run again, the sweep keeps the designs
 * finished before the loss and ends with the bytes of an undisturbed
 * one-process sweep.
 */
#include <errno.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>

#include "mpi_run.h"

#define SWEEP_ARGS "sweep --scene ref4 --set segments=96 " \
	"--grid edge_radius=0,0.02,0.05 --angles 0:88:4 --rays 150000"

static void nap_ms(long ms)
{
	struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };

	nanosleep(&ts, NULL);
}

/* Wait up to s seconds for a file in the scratch folder. */
static int wait_file(const char *name, double s)
{
	char path[256];
	struct stat st;
	int i;

	snprintf(path, sizeof(path), "%s/%s", scratch, name);
	for (i = 0; i < (int)(s * 200); i++) {
		if (stat(path, &st) == 0)
			return 1;
		nap_ms(5);
	}
	return 0;
}

static int read_rc(const char *name)
{
	char path[256];
	FILE *f;
	int rc = -1;

	snprintf(path, sizeof(path), "%s/%s", scratch, name);
	f = fopen(path, "r");
	if (f && fscanf(f, "%d", &rc) != 1)
		rc = -1;
	if (f)
		fclose(f);
	return rc;
}

/*
 * Start the sweep on 2 ranks in the background, send sig to rank 1 once
 * the first design is kept, and wait for the job to end; its exit status.
 */
static int sweep_with_lost_rank(const char *tag, int sig)
{
	long pid;
	int rc, i;

	shell("(timeout 60 mpirun --oversubscribe -n 2 %s --task-timeout 2 "
	      SWEEP_ARGS " --state st_%s --out t_%s.csv > %s.out 2> %s.err;"
	      " echo $? > %s.rc) &", bin("stray-mpi"), tag, tag, tag, tag, tag);
	{
		char first[64];

		snprintf(first, sizeof(first), "st_%s/design_0000.csv", tag);
		assert_true(wait_file(first, 60));
	}
	pid = rank_pid(1);
	assert_true(pid > 0);
	assert_int_equal(kill((pid_t)pid, sig), 0);
	{
		char done[32];

		snprintf(done, sizeof(done), "%s.rc", tag);
		assert_true(wait_file(done, 70));
		nap_ms(50);	/* the echo's write */
		rc = read_rc(done);
	}
	for (i = 0; i < 100 && kill((pid_t)pid, 0) == 0; i++)
		nap_ms(50);	/* mpirun's SIGKILL, then init reaps it */
	if (kill((pid_t)pid, 0) == 0) {	/* never leave it stopped */
		kill((pid_t)pid, SIGKILL);
		fail_msg("rank 1 (pid %ld) outlived its job", pid);
	}
	return rc;
}

/* The undisturbed one-process sweep, and a resumed one equal to it. */
static void check_resume(const char *tag)
{
	char err[32];

	assert_int_equal(shell("timeout 120 %s " SWEEP_ARGS " --state st_ref "
			       "--out ref.csv > ref.out 2>&1", bin("stray")), 0);
	assert_int_equal(shell("timeout 120 mpirun --oversubscribe -n 2 %s "
			       SWEEP_ARGS " --state st_%s --out t_%s.csv > "
			       "%s.out2 2> %s.err2", bin("stray-mpi"), tag, tag,
			       tag, tag), 0);
	snprintf(err, sizeof(err), "%s.err2", tag);
	assert_true(file_has(err, "design 1/3 edge_radius=0: kept"));
	{
		char t[32];

		snprintf(t, sizeof(t), "t_%s.csv", tag);
		assert_true(same_bytes("ref.csv", t));
	}
}

static void test_mpi_stalled_rank(void **state)
{
	(void)state;
	assert_true(sweep_with_lost_rank("stop", SIGSTOP) != 0);
	/* one line of ours, naming the rank and the cure */
	assert_int_equal(shell("grep 'stray-mpi sweep: mpi: rank 1 ' stop.err"
			       " | grep -c 'killed or stalled; --task-timeout'"
			       " | grep -qx 1"), 0);
	check_resume("stop");
}

static void test_mpi_killed_rank(void **state)
{
	(void)state;
	assert_true(sweep_with_lost_rank("kill", SIGKILL) != 0);
	assert_true(file_has("kill.err", "rank 1"));
	assert_true(file_has("kill.err", "signal 9"));
	check_resume("kill");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_mpi_stalled_rank),
		cmocka_unit_test(test_mpi_killed_rank),
	};

	return mpi_run_group(tests);
}
