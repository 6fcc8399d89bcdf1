/*
 * test_diag_reweight.c - hidden causes that the diagnosis re-evaluates by
 * re-weighting recorded paths or post-processing the curve: reflectance,
 * floor, angle offset, light leak.  Each must be named alone with its
 * parameter inside the stated interval.
 */
#include "diag_test.h"

static void test_reflectance(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.sets[c.n_sets++] = "reflectance=0.06";
	j = diagnose_truth(&c);
	expect_one(__func__, j, "reflectance", "reflectance", 0.06);
	cJSON_Delete(j);
}

static void test_floor(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.floor = 8e-6;
	j = diagnose_truth(&c);
	expect_one(__func__, j, "floor", "log10_floor", log10(8e-6));
	cJSON_Delete(j);
}

static void test_angle_offset(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.angle_offset_deg = 0.4;
	j = diagnose_truth(&c);
	expect_one(__func__, j, "angle_offset", "offset_deg", 0.4);
	cJSON_Delete(j);
}

static void test_light_leak(void **state)
{
	struct truth_config c;
	const cJSON *k;
	cJSON *j;
	int in = 0;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.leak_level = 4e-5;	/* thesis §4: a raised floor 20-35 deg */
	c.leak_lo_deg = 29.0;
	c.leak_hi_deg = 41.0;
	j = diagnose_truth(&c);
	expect_one(__func__, j, "light_leak", "log10_level", log10(4e-5));
	k = cause(j, "light_leak");
	param(k, "theta_lo_deg", 29.0, &in);	/* between 28 and 30 */
	assert_true(in);
	param(k, "theta_hi_deg", 41.0, &in);	/* between 40 and 45 */
	assert_true(in);
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_reflectance),
		cmocka_unit_test(test_floor),
		cmocka_unit_test(test_angle_offset),
		cmocka_unit_test(test_light_leak),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
