/*
 * test_angles.c - `--angles LIST`: values, start:stop:step ranges with the
 * stop included, merged joints, and one clear error per bad item.
 */
#include <stdlib.h>

#include "tracer_test.h"
#include "tracer/angles.h"

static void test_angles_values_and_ranges(void **state)
{
	double *a;
	size_t n;

	(void)state;
	assert_int_equal(tracer_angles_parse("0,5,10:30:0.5", &a, &n, NULL), 0);
	assert_int_equal(n, 43);
	assert_near(a[0], 0.0, 0.0);
	assert_near(a[2], 10.0, 0.0);
	assert_near(a[3], 10.5, 1e-12);
	assert_near(a[42], 30.0, 1e-9);
	free(a);
	/* the default sweep: 0-30 every 5, 30-90 every 0.5 */
	assert_int_equal(tracer_angles_parse(TRACER_ANGLES_DEFAULT, &a, &n,
					     NULL), 0);
	assert_int_equal(n, 127);
	assert_near(a[6], 30.0, 1e-9);
	assert_near(a[7], 30.5, 1e-9);
	assert_near(a[126], 90.0, 1e-9);
	free(a);
	/* unsorted input is sorted, duplicates merged */
	assert_int_equal(tracer_angles_parse("20,5,5", &a, &n, NULL), 0);
	assert_int_equal(n, 2);
	assert_near(a[0], 5.0, 0.0);
	free(a);
}

static void expect_error(const char *list, const char *text)
{
	struct stray_error err;
	double *a = NULL;
	size_t n;

	stray_error_clear(&err);
	assert_int_equal(tracer_angles_parse(list, &a, &n, &err), STRAY_EINVAL);
	assert_null(a);
	assert_string_equal(err.field, "--angles");
	if (text)
		assert_string_equal(err.text, text);
}

static void test_angles_bad_items_named(void **state)
{
	(void)state;
	expect_error("0,abc,5", "abc");
	expect_error("10:5:1", "10:5:1");
	expect_error("10:30:0", "10:30:0");
	expect_error("5:10", "5:10");
	expect_error("1:2:3:4", "1:2:3:4");
	expect_error("nan", "nan");
	expect_error("0,200", NULL);
	expect_error("", NULL);
	expect_error("0:1e9:1e-3", "0:1e9:1e-3");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_angles_values_and_ranges),
		cmocka_unit_test(test_angles_bad_items_named),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
