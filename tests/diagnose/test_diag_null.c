/*
 * test_diag_null.c - nothing hidden, nothing named: a curve from the
 * nominal ref4 (its own seed, noise and floor) is "no significant
 * discrepancy", with no cause.
 */
#include "diag_test.h"

static void test_nothing_hidden(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	j = diagnose_truth(&c);
	show(__func__, j);
	assert_false(flag(j, "significant"));
	assert_int_equal(n_causes(j), 0);
	assert_true(num(j, "rms_after") == num(j, "rms_before"));
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_nothing_hidden),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
