/*
 * test_diag_two_causes.c - issue 5's "Done when": on ref4, a curve made
 * with reflectance 0.08 and knife-edge radius 0.05 mm is diagnosed as
 * exactly those two causes, both values inside their intervals, and the
 * RMS log residual cut at least 5x.
 */
#include "diag_test.h"

static void test_reflectance_and_knife_edge(void **state)
{
	struct truth_config c;
	const cJSON *r, *k;
	cJSON *j;
	int in_r = 0, in_k = 0;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.sets[c.n_sets++] = "reflectance=0.08";
	c.sets[c.n_sets++] = "edge_radius=0.05";
	j = diagnose_truth(&c);
	show(__func__, j);
	r = cause(j, "reflectance");
	k = cause(j, "knife_edge_radius");
	assert_true(flag(j, "significant"));
	assert_int_equal(n_causes(j), 2);
	assert_non_null(r);
	assert_non_null(k);
	param(r, "reflectance", 0.08, &in_r);
	param(k, "radius_mm", 0.05, &in_k);
	assert_true(in_r);
	assert_true(in_k);
	assert_true(num(j, "rms_before") >= 5.0 * num(j, "rms_after"));
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_reflectance_and_knife_edge),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
