/*
 * test_root.c - Brent's method (root.c) against analytic inverses.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../test_util.h"

#include "stray/root.h"

struct target {
	double a;
	int calls;
};

static int cube_minus_a(double x, void *ctx, double *y)
{
	struct target *t = ctx;

	t->calls++;
	*y = x * x * x - t->a;
	return STRAY_OK;
}

static int exp_minus_a(double x, void *ctx, double *y)
{
	struct target *t = ctx;

	t->calls++;
	*y = exp(x) - t->a;
	return STRAY_OK;
}

/* A step function: Brent must still converge by bisection to the jump. */
static int step_at_a(double x, void *ctx, double *y)
{
	struct target *t = ctx;

	t->calls++;
	*y = x < t->a ? -1.0 : 1.0;
	return STRAY_OK;
}

static int fails(double x, void *ctx, double *y)
{
	(void)x;
	(void)ctx;
	*y = 0.5;
	return STRAY_ENOCONV;
}

static void test_brent_cube_root(void **state)
{
	const double as[] = { 2.0, 27.0, 1e-6, 1e6, -8.0 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(as) / sizeof(as[0]); i++) {
		struct target t = { as[i], 0 };
		struct stray_root_result r;
		struct stray_error err;

		stray_error_clear(&err);
		assert_int_equal(stray_root_brent(cube_minus_a, &t, -200.0, 200.0,
						  1e-14, &r, &err), STRAY_OK);
		assert_near(r.x, cbrt(as[i]), 1e-12 * fmax(1.0, fabs(r.x)));
		assert_true(t.calls <= 80);	/* superlinear, not bisection */
	}
}

static void test_brent_logarithm(void **state)
{
	struct target t = { 1e-200, 0 };
	struct stray_root_result r;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_root_brent(exp_minus_a, &t, -700.0, 10.0, 1e-13,
					  &r, &err), STRAY_OK);
	assert_near(r.x, log(1e-200), 1e-11);
}

static void test_brent_discontinuous_still_brackets(void **state)
{
	struct target t = { 0.3, 0 };
	struct stray_root_result r;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_root_brent(step_at_a, &t, 0.0, 1.0, 1e-12, &r,
					  &err), STRAY_OK);
	assert_near(r.x, 0.3, 1e-11);
	assert_true(r.iterations < 200);
}

static void test_brent_unbracketed_is_erange(void **state)
{
	struct target t = { 8.0, 0 };
	struct stray_root_result r;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_root_brent(cube_minus_a, &t, 3.0, 5.0, 1e-12, &r,
					  &err), STRAY_ERANGE);
	assert_int_equal(err.code, STRAY_ERANGE);
	stray_error_clear(&err);
	assert_int_equal(stray_root_brent(cube_minus_a, &t, 5.0, 3.0, 1e-12, &r,
					  &err), STRAY_EINVAL);
	stray_error_clear(&err);
	assert_int_equal(stray_root_brent(cube_minus_a, &t, NAN, 3.0, 1e-12, &r,
					  &err), STRAY_EINVAL);
}

static void test_brent_passes_callback_failure_through(void **state)
{
	struct stray_root_result r;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_root_brent(fails, NULL, 0.0, 1.0, 1e-12, &r, &err),
			 STRAY_ENOCONV);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_brent_cube_root),
		cmocka_unit_test(test_brent_logarithm),
		cmocka_unit_test(test_brent_discontinuous_still_brackets),
		cmocka_unit_test(test_brent_unbracketed_is_erange),
		cmocka_unit_test(test_brent_passes_callback_failure_through),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
