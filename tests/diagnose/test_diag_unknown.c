/*
 * test_diag_unknown.c - a hidden effect that no cause in the registry can
 * represent (a multiplicative dip over 45-55 deg, as from an obstruction
 * of part of the sweep): the diagnosis must report an unexplained
 * residual where it sits and name no cause.
 */
#include "diag_test.h"

static void test_dip_not_in_registry(void **state)
{
	struct truth_config c;
	cJSON *j;
	double at;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.dip_factor = 0.5;
	c.dip_lo_deg = 44.0;
	c.dip_hi_deg = 56.0;
	j = diagnose_truth(&c);
	show(__func__, j);
	assert_true(flag(j, "significant"));
	assert_false(flag(j, "explained"));
	assert_int_equal(n_causes(j), 0);
	at = num(j, "worst_theta_deg");
	assert_true(at >= 44.0 && at <= 56.0);
	assert_true(num(j, "worst_pull") < 0.0);	/* measured below */
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_dip_not_in_registry),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
