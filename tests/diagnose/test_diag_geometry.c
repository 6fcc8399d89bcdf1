/*
 * test_diag_geometry.c - hidden causes that need a re-trace: knife-edge
 * radius alone, a narrower detector acceptance cone, the bevel on the
 * other face, a forward-scattering (ABg) coating, a rotation centre
 * behind the aperture.
 */
#include "diag_test.h"

static void test_knife_edge(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.sets[c.n_sets++] = "edge_radius=0.1";
	j = diagnose_truth(&c);
	expect_one(__func__, j, "knife_edge_radius", "radius_mm", 0.1);
	cJSON_Delete(j);
}

static void test_acceptance_cone(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.sets[c.n_sets++] = "accept_half_angle_deg=40";
	j = diagnose_truth(&c);
	expect_one(__func__, j, "acceptance_cone", "half_angle_deg", 40.0);
	cJSON_Delete(j);
}

static void test_bevel_face(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.sets[c.n_sets++] = "bevel_face=upper";
	j = diagnose_truth(&c);
	expect_one(__func__, j, "bevel_face", NULL, 0.0);
	cJSON_Delete(j);
}

static void test_abg_scatter(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.abg_g = 2.0;
	j = diagnose_truth(&c);
	expect_one(__func__, j, "abg_scatter", "g", 2.0);
	cJSON_Delete(j);
}

static void test_pivot_offset(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.pivot_mm = 3.5;
	j = diagnose_truth(&c);
	expect_one(__func__, j, "pivot_offset", "offset_mm", 3.5);
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_knife_edge),
		cmocka_unit_test(test_acceptance_cone),
		cmocka_unit_test(test_bevel_face),
		cmocka_unit_test(test_abg_scatter),
		cmocka_unit_test(test_pivot_offset),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
