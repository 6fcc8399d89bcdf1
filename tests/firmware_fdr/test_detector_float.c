/*
 * test_detector_float.c - the detector tables in the flight module as it
 * flies: this binary builds firmware_fdr and libstray's core with
 * STRAY_REAL_FLOAT (single precision, as on the Cortex-M4F), so it links
 * no ground code; the tables come from `stray firmware-table --detector D
 * --out-bin` ($STRAY_BIN).  Each is accepted at init, its grid answers at
 * the nodes in float, and the Sun's flag turns at the table's exclusion
 * angle; another exposure than the grid's is an invalid frame.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "../tools/run_cli.h"
#include "../scratch.h"
#include "fdrfw/fdrfw.h"
#include "source_fdr.h"

STRAY_STATIC_ASSERT(sizeof(stray_real) == 4, built_as_on_the_target);

static char dir[64];

/* The table stray firmware-table writes for the detector arguments. */
static void table_for(char *const det_args[], struct fdrfw_table *t)
{
	static uint8_t blob[FDRFW_BLOB_SIZE + 16];
	char out[128];
	char *argv[16] = { "stray", "firmware-table", "--curve",
			   "tests/vectors/fdrfw_curve.csv", "--out-bin", out };
	struct cli_run r;
	FILE *f;
	size_t n;
	int i = 6, k;

	snprintf(out, sizeof(out), "%s/t.bin", dir);
	for (k = 0; det_args[k]; k++)
		argv[i++] = det_args[k];
	argv[i] = NULL;
	if (run_stray(&r, argv) != 0)
		fprintf(stderr, "%s", r.err);
	assert_int_equal(r.status, 0);
	f = fopen(out, "rb");
	assert_non_null(f);
	n = fread(blob, 1, sizeof(blob), f);
	fclose(f);
	assert_int_equal(fdrfw_table_parse(blob, n, t), FDRFW_OK);
}

static void check_detector(char *const det_args[], uint32_t kind)
{
	static struct fdrfw_table t;
	struct fdrfw_source_result r;
	struct fdrfw_ctx ctx;
	stray_real f;
	int i;

	table_for(det_args, &t);
	assert_int_equal(t.detector, kind);
	assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
	f = (stray_real)t.f_sun_ph_s_m2;
	/* the grid's answers at its nodes, in float */
	for (i = 0; i < FDRFW_DET_MAX; i++) {
		double per = (double)t.f_sun_ph_s_m2 * (double)t.t_exp_nominal_s *
			     (double)t.a_px_m2 * (double)t.k_px;
		float a = (float)(exp((double)t.det_u0 + i * (double)t.det_du) /
				  per);
		float lf = t.det_ln_false[i];

		fdrfw_grid_source(&ctx, f, a, a, &r);
		assert_true(fabsf(r.p_drs - t.det_p_drs[i]) <= 2e-4f);
		if (lf > FDRFW_DET_LN_FLOOR + 1.0f)
			assert_true(fabsf(r.ln_fdr - lf) <=
				    2e-3f + 2e-4f * fabsf(lf));
	}
	/* the Sun's flag turns at the table's exclusion angle */
	assert_int_equal(fdrfw_point_source(&ctx, f,
		t.exclusion_sun_deg - 0.3f, 0, &r), 0);
	assert_true(r.excluded);
	assert_int_equal(fdrfw_point_source(&ctx, f,
		t.exclusion_sun_deg + 0.3f, 0, &r), 0);
	assert_false(r.excluded);
	assert_int_equal(fdrfw_set_exposure(&ctx, 0.5f * t.t_exp_nominal_s),
			 FDRFW_EINPUT);
}

static void test_window(void **state)
{
	char *const a[] = { "--detector", "window", NULL };

	(void)state;
	check_detector(a, 1u);
}

static void test_threshold(void **state)
{
	char *const a[] = { "--detector", "threshold", NULL };

	(void)state;
	check_detector(a, 2u);
}

static void test_tetra3(void **state)
{
	char *const a3[] = { "--detector", "tetra3", NULL };
	char *const a5[] = { "--detector", "tetra3", "--detector-sigma", "5",
			     NULL };

	(void)state;
	check_detector(a3, 3u);
	check_detector(a5, 3u);
}

/* The thesis table flies eq. 2.18 as before, at any exposure. */
static void test_thesis_unchanged(void **state)
{
	static struct fdrfw_table t;
	char *const none[] = { NULL };
	struct fdrfw_ctx ctx;

	(void)state;
	table_for(none, &t);
	assert_int_equal(t.detector, 0u);
	assert_int_equal(t.n_det, 0u);
	assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
	assert_int_equal(fdrfw_set_exposure(&ctx, 0.5f * t.t_exp_nominal_s),
			 FDRFW_OK);
}

static int setup(void **state)
{
	(void)state;
	snprintf(dir, sizeof(dir), "/tmp/stray_detfl_XXXXXX");
	return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_window),
		cmocka_unit_test(test_threshold),
		cmocka_unit_test(test_tetra3),
		cmocka_unit_test(test_thesis_unchanged),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
