/*
 * test_mpi_trace.c - mpirun on localhost with 2, 3 and 4 ranks
 * (oversubscribed on 2 cores) gives the bytes of a one-process run with
 * the same seed: `stray trace` curves with a lens, angle chunks and the
 * pilot guide, and a `stray sweep` (its designs farmed together): table,
 * curves and progress.  Every command has a timeout.
 */
#include <signal.h>

#include "mpi_run.h"

#define TRACE_ARGS "trace --scene ref4 --set segments=96 --angles 0:80:8 " \
	"--rays 30000 --seed 7 --lens lens.csv"
#define SWEEP_ARGS "sweep --scene ref4 --set segments=96 " \
	"--grid bevel_face=lower,upper --grid reflectance=0.04,0.08 " \
	"--angles 0:88:4 --alpha-at 20,40 --rays 20000"

static void write_lens(void)
{
	assert_int_equal(shell("printf '# kind: lens\\ntheta_deg,alpha\\n"
			       "0,1\\n20,0.6\\n40,0.2\\n90,0.05\\n' > lens.csv"),
			 0);
}

static void test_mpi_trace_identical(void **state)
{
	static const struct { int n; const char *extra; } runs[] = {
		{ 2, "" }, { 3, "--angle-chunks 3" }, { 4, "--angle-chunks 2" },
	};
	char out[32];
	size_t i;

	(void)state;
	write_lens();
	assert_int_equal(shell("timeout 60 %s " TRACE_ARGS " --threads 1 "
			       "--out one.csv", bin("stray")), 0);
	/* the same binary without mpirun: a singleton, one rank */
	assert_int_equal(shell("timeout 60 %s " TRACE_ARGS " --out single.csv",
			       bin("stray-mpi")), 0);
	assert_true(same_bytes("one.csv", "single.csv"));
	for (i = 0; i < sizeof(runs) / sizeof(runs[0]); i++) {
		snprintf(out, sizeof(out), "n%d.csv", runs[i].n);
		assert_int_equal(shell("timeout 90 mpirun --oversubscribe -n %d "
				       "%s --stats %s " TRACE_ARGS " --out %s "
				       "2> n%d.err", runs[i].n,
				       bin("stray-mpi"), runs[i].extra, out,
				       runs[i].n), 0);
		if (!same_bytes("one.csv", out))
			fail_msg("%d ranks: %s differs from one.csv",
				 runs[i].n, out);
	}
	/* the other ranks did take pieces (a real distribution) */
	assert_false(file_has("n4.err", "remote_pieces 0 "));
	assert_true(file_has("n4.err", "stray-mpi: stats: ranks 4"));
}

/* Strategy B (--light-paths) through the farm: the pilot pieces return
 * B's statistics, rank 0 sizes B and sends the ratios with the guide;
 * 2 ranks, 3 ranks in angle chunks (the pilot's casts summed once per
 * batch: tracer_light_alloc reads them) and one rank give the bytes of
 * one process, and B did run (the curve is not --no-light-paths'). */
#define LIGHT_ARGS "trace --scene ref4 --set segments=96 " \
	"--angles 0:80:8,88.5,89,89.5 --rays 30000 --seed 7"

static void test_mpi_trace_light_paths(void **state)
{
	(void)state;
	assert_int_equal(shell("timeout 60 %s " LIGHT_ARGS " --light-paths "
			       "--threads 1 --out l1.csv", bin("stray")), 0);
	assert_int_equal(shell("timeout 60 %s " LIGHT_ARGS " --no-light-paths "
			       "--out a1.csv", bin("stray")), 0);
	assert_false(same_bytes("l1.csv", "a1.csv"));
	assert_int_equal(shell("timeout 60 %s " LIGHT_ARGS " --light-paths "
			       "--out ls.csv", bin("stray-mpi")), 0);
	assert_true(same_bytes("l1.csv", "ls.csv"));
	assert_int_equal(shell("timeout 90 mpirun --oversubscribe -n 2 %s "
			       LIGHT_ARGS " --light-paths --out l2.csv",
			       bin("stray-mpi")), 0);
	assert_true(same_bytes("l1.csv", "l2.csv"));
	assert_int_equal(shell("timeout 90 mpirun --oversubscribe -n 3 %s "
			       "--angle-chunks 3 " LIGHT_ARGS " --light-paths "
			       "--out l3.csv", bin("stray-mpi")), 0);
	assert_true(same_bytes("l1.csv", "l3.csv"));
}

/* A different seed changes the bytes: the comparison can fail. */
static void test_mpi_trace_seed_matters(void **state)
{
	(void)state;
	write_lens();
	assert_int_equal(shell("timeout 90 mpirun --oversubscribe -n 2 %s "
			       TRACE_ARGS " --seed 8 --out seed8.csv",
			       bin("stray-mpi")), 0);
	assert_int_equal(shell("timeout 60 %s " TRACE_ARGS " --out seed7.csv",
			       bin("stray")), 0);
	assert_false(same_bytes("seed7.csv", "seed8.csv"));
}

/* The designs farmed together (one set: one stats line) give the table,
 * every design's curve and the progress lines of a one-process sweep. */
static void test_mpi_sweep_identical(void **state)
{
	static const int ranks[] = { 2, 4 };
	char name[64], one[64];
	size_t i;
	int d;

	(void)state;
	assert_int_equal(shell("timeout 120 %s " SWEEP_ARGS " --state st1 "
			       "--out sweep1.csv > sweep1.txt 2> sweep1.err",
			       bin("stray")), 0);
	for (i = 0; i < sizeof(ranks) / sizeof(ranks[0]); i++) {
		int n = ranks[i];

		assert_int_equal(shell("timeout 120 mpirun --oversubscribe -n %d "
				       "%s --stats " SWEEP_ARGS " --state st%d "
				       "--out sweep%d.csv --json > sweep%d.json "
				       "2> sweep%d.err", n, bin("stray-mpi"), n,
				       n, n, n), 0);
		snprintf(name, sizeof(name), "sweep%d.csv", n);
		assert_true(same_bytes("sweep1.csv", name));
		for (d = 0; d < 4; d++) {
			snprintf(one, sizeof(one), "st1/design_%04d.csv", d);
			snprintf(name, sizeof(name), "st%d/design_%04d.csv", n,
				 d);
			if (!same_bytes(one, name))
				fail_msg("%d ranks: %s differs", n, name);
		}
		snprintf(name, sizeof(name), "sweep%d.json", n);
		assert_true(file_has(name, "\"best\":"));
		/* progress in design order, as `stray sweep` prints it */
		assert_int_equal(shell("grep '^stray sweep: design' sweep%d.err "
				       "| cmp -s - sweep1.err", n), 0);
		/* one set of traces, not a farm per design */
		assert_int_equal(shell("grep -c 'stray-mpi: stats' sweep%d.err "
				       "| grep -qx 1", n), 0);
	}
	assert_false(file_has("sweep4.err", "remote_pieces 0 "));
}

/* Paths, dumps and maps are not distributed: one clear line, exit 2. */
static void test_mpi_refuses_path_records(void **state)
{
	(void)state;
	assert_int_equal(shell("timeout 60 mpirun --oversubscribe -n 2 %s "
			       "trace --scene ref4 --rays 2000 --angles 0,30 "
			       "--top 3 > top.out 2> top.err",
			       bin("stray-mpi")), 2);
	assert_true(file_has("top.err", "need one rank"));
}

/* A bad design in the middle of a farmed sweep: the line `stray sweep`
 * gives, exit 2, and the job ends without MPI_Abort (the ranks hand back
 * what they hold first). */
static void test_mpi_sweep_bad_design(void **state)
{
	(void)state;
	assert_int_equal(shell("timeout 90 mpirun --oversubscribe -n 3 %s "
			       SWEEP_ARGS " --grid edge_radius=0,0.01,abc "
			       "--state bad > bad.out 2> bad.err",
			       bin("stray-mpi")), 2);
	assert_true(file_has("bad.err", "stray-mpi sweep: --set"));
	assert_true(file_has("bad.err", "edge_radius=abc"));
	assert_true(file_has("bad.err", "value is not a finite number"));
	/* mpirun's notice of a normal end with a nonzero code: after an
	 * MPI_Abort it says otherwise */
	assert_true(file_has("bad.err", "terminated normally"));
	assert_false(file_has("bad.err", "MPI_ABORT"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_mpi_trace_identical),
		cmocka_unit_test(test_mpi_trace_seed_matters),
		cmocka_unit_test(test_mpi_trace_light_paths),
		cmocka_unit_test(test_mpi_sweep_identical),
		cmocka_unit_test(test_mpi_refuses_path_records),
		cmocka_unit_test(test_mpi_sweep_bad_design),
	};

	return mpi_run_group(tests);
}
