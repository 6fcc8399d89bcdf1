/*
 * test_mpi_diagnose.c - `mpirun -n N stray-mpi diagnose` on localhost
 * (2 and 3 ranks, oversubscribed on 2 cores, angle chunks too) gives the
 * report of a one-process `stray diagnose` with the same rays and seed,
 * byte for byte but for the trace timing; its traces really are split
 * (other ranks trace pieces, path records included).  Every command has
 * a timeout.
 */
#include "mpi_run.h"

#define DIAG_ARGS "diagnose m.csv --scene ref4 --rays 20000 --json"

/* A measured curve with a reflectance the diagnosis is not told. */
static void write_measured(void)
{
	assert_int_equal(shell("timeout 60 %s trace --scene ref4 "
			       "--set reflectance=0.08 --angles 0:85:10 "
			       "--rays 100000 --out truth.csv > /dev/null",
			       bin("stray")), 0);
	assert_int_equal(shell("timeout 30 %s photometer --truth truth.csv "
			       "--out m.csv --seed 3", bin("stray")), 0);
}

/* The report without its timing line (wall-clock seconds differ). */
static void strip_timing(const char *in, const char *out)
{
	/* and the provenance's command line, which names each run's own */
	assert_int_equal(shell("grep -v -e '\"trace_seconds\"' "
			       "-e '\"command\":' %s > %s", in, out), 0);
	assert_true(file_has(in, "\"trace_seconds\""));
}

static void test_mpi_diagnose_identical(void **state)
{
	static const struct { int n; const char *extra; } runs[] = {
		{ 2, "--stats" }, { 3, "--stats --angle-chunks 3" },
	};
	char out[32], cut[32], err[32];
	size_t i;

	(void)state;
	write_measured();
	assert_int_equal(shell("timeout 120 %s " DIAG_ARGS " --seed 5 "
			       "> one.json", bin("stray")), 0);
	strip_timing("one.json", "one.cut");
	assert_true(file_has("one.json", "\"name\":\t\"reflectance\""));
	for (i = 0; i < sizeof(runs) / sizeof(runs[0]); i++) {
		snprintf(out, sizeof(out), "diag%d.json", runs[i].n);
		snprintf(cut, sizeof(cut), "diag%d.cut", runs[i].n);
		snprintf(err, sizeof(err), "diag%d.err", runs[i].n);
		assert_int_equal(shell("timeout 180 mpirun --oversubscribe -n %d "
				       "%s %s " DIAG_ARGS " --seed 5 > %s 2> %s",
				       runs[i].n, bin("stray-mpi"),
				       runs[i].extra, out, err), 0);
		strip_timing(out, cut);
		assert_true(same_bytes("one.cut", cut));
		/* the traces went to the farm and other ranks took pieces */
		assert_int_equal(shell("grep -q 'stats: ranks %d ' %s",
				       runs[i].n, err), 0);
		assert_int_equal(shell("grep 'stats:' %s | grep -vq "
				       "'remote_pieces 0 '", err), 0);
	}
}

/* The comparison can fail: another seed gives other numbers. */
static void test_mpi_diagnose_seed_matters(void **state)
{
	(void)state;
	assert_int_equal(shell("timeout 180 mpirun --oversubscribe -n 2 %s "
			       DIAG_ARGS " --seed 6 > seed6.json",
			       bin("stray-mpi")), 0);
	strip_timing("seed6.json", "seed6.cut");
	assert_false(same_bytes("one.cut", "seed6.cut"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_mpi_diagnose_identical),
		cmocka_unit_test(test_mpi_diagnose_seed_matters),
	};

	return mpi_run_group(tests);
}
