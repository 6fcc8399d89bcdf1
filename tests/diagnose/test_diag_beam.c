/*
 * test_diag_beam.c - issue 17 item 6: the lab beam diverges by 1.5 deg
 * (a uniform disk of directions, traced direction by direction by the
 * truth generator) and the diagnosis is not told: it must name
 * beam_divergence alone with an interval holding 1.5 deg and cut the
 * RMS log residual.  The logged sweep is 1 deg apart over the cut-off,
 * where a divergent beam shows.
 */
#include "diag_test.h"

static const double theta[] = {
	0, 5, 10, 14, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28,
	30, 35, 40, 50, 60, 70
};
#define N_THETA (sizeof(theta) / sizeof(theta[0]))

static void test_beam_divergence(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, theta, N_THETA);
	c.beam_half_deg = 1.5;
	c.n_paths = 300000;
	j = diagnose_truth(&c);
	expect_one(__func__, j, "beam_divergence", "half_angle_deg", 1.5);
	assert_true(num(j, "rms_before") >= 2.0 * num(j, "rms_after"));
	cJSON_Delete(j);
}

/* A non-uniform beam: a disk of 2.5 deg whose intensity falls off as a
 * Gaussian of 1/e^2 radius 1.0 deg. */
static void test_beam_profile(void **state)
{
	struct truth_config c;
	const cJSON *b;
	cJSON *j;
	int inside = 0;

	(void)state;
	truth_defaults(&c, theta, N_THETA);
	c.beam_half_deg = 2.5;
	c.beam_gauss_deg = 1.0;
	c.n_paths = 300000;
	j = diagnose_truth(&c);
	show(__func__, j);
	b = cause(j, "beam_profile");
	assert_true(flag(j, "significant"));
	assert_int_equal(n_causes(j), 1);
	assert_non_null(b);
	param(b, "gauss_radius_deg", 1.0, &inside);
	assert_true(inside);
	assert_true(num(j, "rms_before") >= 2.0 * num(j, "rms_after"));
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_beam_divergence),
		cmocka_unit_test(test_beam_profile),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
