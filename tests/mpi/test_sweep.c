/*
 * test_sweep.c - `stray sweep` without MPI: the design grid's order and
 * its bad input, one-line errors for bad values, and resumption that
 * keeps only what matches (a changed run or a damaged file is retraced).
 */
#include "tracer/design_grid.h"
#include "mpi_run.h"

#define SWEEP "sweep --scene ref4 --set segments=64 --set bevel_face=upper " \
	"--angles 0:88:4 --alpha-at 30 --rays 3000 --batches 8 --threads 1"

static void test_grid_order(void **state)
{
	struct design_grid g;
	struct stray_error err;
	char label[256];

	(void)state;
	memset(&g, 0, sizeof(g));
	stray_error_clear(&err);
	assert_int_equal(design_grid_add(&g, "edge_radius=0,0.02,0.05", &err), 0);
	assert_int_equal(design_grid_add(&g, "bevel_face=lower,upper", &err), 0);
	assert_int_equal(g.n_designs, 6);
	design_grid_label(&g, 0, label, sizeof(label));
	assert_string_equal(label, "edge_radius=0 bevel_face=lower");
	design_grid_label(&g, 1, label, sizeof(label));
	assert_string_equal(label, "edge_radius=0 bevel_face=upper");
	design_grid_label(&g, 5, label, sizeof(label));
	assert_string_equal(label, "edge_radius=0.05 bevel_face=upper");
	assert_int_equal(design_grid_add(&g, "reflectance", &err), STRAY_EINVAL);
	stray_error_clear(&err);
	assert_int_equal(design_grid_add(&g, "=1,2", &err), STRAY_EINVAL);
	stray_error_clear(&err);
	assert_int_equal(design_grid_add(&g, "reflectance=0.04,,0.08", &err),
			 STRAY_EINVAL);
	assert_int_equal(g.n_designs, 6);
}

static void test_sweep_bad_input(void **state)
{
	(void)state;
	/* a value the baffle refuses: one line naming the parameter */
	assert_int_not_equal(shell("%s " SWEEP " --grid edge_radius=0,abc "
				   "--state b1 > b1.out 2> b1.err",
				   bin("stray")), 0);
	assert_int_equal(shell("wc -l < b1.err | grep -qx 2"), 0);
	assert_true(file_has("b1.err", "stray sweep:"));
	assert_true(file_has("b1.err", "not a finite number"));
	assert_int_not_equal(shell("%s " SWEEP " --grid no_such_key=1 "
				   "--state b2 2> b2.err", bin("stray")), 0);
	assert_true(file_has("b2.err", "unknown baffle parameter"));
	assert_int_equal(shell("%s " SWEEP " --state b3 2> b3.err",
			       bin("stray")), 2);
	assert_true(file_has("b3.err", "--grid"));
	assert_int_not_equal(shell("%s " SWEEP " --grid reflectance=0.04 "
				   "--state /proc/no/such 2> b4.err",
				   bin("stray")), 0);
	assert_true(file_has("b4.err", "--state"));
}

static void test_sweep_resume_checks_key(void **state)
{
	(void)state;
	assert_int_equal(shell("%s " SWEEP " --grid reflectance=0.04,0.08 "
			       "--state r --out r1.csv > r1.out 2> r1.err",
			       bin("stray")), 0);
	assert_true(file_has("r1.err", "design 2/2 reflectance=0.08: traced"));
	/* the darker coating attenuates more: it must win */
	assert_true(file_has("r1.out", "best: design 0 (reflectance=0.04)"));
	/* same run: both kept, same table */
	assert_int_equal(shell("%s " SWEEP " --grid reflectance=0.04,0.08 "
			       "--state r --out r2.csv 2> r2.err > /dev/null",
			       bin("stray")), 0);
	assert_true(file_has("r2.err", "design 1/2 reflectance=0.04: kept"));
	assert_true(same_bytes("r1.csv", "r2.csv"));
	/* a damaged file and another seed: traced again, never trusted */
	assert_int_equal(shell("head -c 40 r/design_0000.csv > t && "
			       "mv t r/design_0000.csv"), 0);
	assert_int_equal(shell("%s " SWEEP " --grid reflectance=0.04,0.08 "
			       "--state r --out r3.csv 2> r3.err > /dev/null",
			       bin("stray")), 0);
	assert_true(file_has("r3.err", "design 1/2 reflectance=0.04: traced"));
	assert_true(file_has("r3.err", "design 2/2 reflectance=0.08: kept"));
	assert_true(same_bytes("r1.csv", "r3.csv"));
	assert_int_equal(shell("%s " SWEEP " --seed 9 --grid "
			       "reflectance=0.04,0.08 --state r 2> r4.err "
			       "> /dev/null", bin("stray")), 0);
	assert_true(file_has("r4.err", "design 2/2 reflectance=0.08: traced"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_grid_order),
		cmocka_unit_test(test_sweep_bad_input),
		cmocka_unit_test(test_sweep_resume_checks_key),
	};

	return mpi_run_group(tests);
}
