/*
 * test_curve.c - alpha_lens = P(theta)/P(0) (thesis eq. 3.12), the noise
 * floor sigma(theta)/Pbar(0) (eq. 3.13-3.15), propagated errors and the
 * linear source drift seen by on-axis revisits, against closed forms.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

#include "stray/reduce_curve.h"
#include "test_util.h"

static void test_curve_single_reference(void **state)
{
	const struct stray_visit v[] = {
		{ 2.0, 1, 30.0, 4.0, 3.0, 100 },
		{ 0.0, 0, 200.0, 16.0, 5.0, 100 },
	};
	struct stray_curve_point p[2];
	struct stray_drift d;
	size_t n;
	double a = 30.0 / 200.0;

	(void)state;
	assert_int_equal(stray_reduce_curve(v, 2, p, &n, &d, NULL), STRAY_OK);
	assert_int_equal(n, 2);
	assert_near(p[0].theta_deg, 0.0, 0);	/* sorted */
	assert_near(p[0].alpha, 1.0, 0);
	assert_near(p[1].alpha, a, 1e-15);	/* eq. 3.12 */
	/* relative variances add: 4/30^2 + 16/200^2 */
	assert_near(p[1].sigma, a * sqrt(4.0 / 900.0 + 16.0 / 40000.0), 1e-15);
	/* eq. 3.15: sigma / Pbar(0), Pbar(0) = 200 / 100 */
	assert_near(p[1].noise_floor, 3.0 / 2.0, 1e-15);
	assert_near(p[0].noise_floor, 5.0 / 2.0, 1e-15);
	assert_false(d.fitted);
	assert_near(d.p0_rel_sigma, 4.0 / 200.0, 1e-15);
}

static void test_curve_drift_line(void **state)
{
	/* P(0) rises 10% linearly with the order; alpha(5 deg) = 0.5. */
	const struct stray_visit v[] = {
		{ 0.0, 0, 100.0, 1e-6, 1.0, 10 },
		{ 5.0, 5, 52.5, 1e-6, 1.0, 10 },
		{ 0.0, 10, 110.0, 1e-6, 1.0, 10 },
	};
	struct stray_curve_point p[3];
	struct stray_drift d;
	size_t n;

	(void)state;
	assert_int_equal(stray_reduce_curve(v, 3, p, &n, &d, NULL), STRAY_OK);
	assert_int_equal(n, 2);
	assert_int_equal(p[0].n_visits, 2);
	assert_near(p[1].alpha, 0.5, 1e-12);
	assert_true(d.fitted && d.detected);
	assert_near(d.rel_change, 0.1, 1e-12);
	assert_near(d.p0, 100.0, 1e-9);
}

static void test_curve_repeats_weighted(void **state)
{
	const struct stray_visit v[] = {
		{ 0.0, 0, 100.0, 0.0, 1.0, 10 },
		{ 3.0, 1, 20.0, 1.0, 1.0, 10 },
		{ 3.0, 2, 30.0, 4.0, 1.0, 10 },
	};
	struct stray_curve_point p[3];
	struct stray_drift d;
	size_t n;
	double w1 = 1.0 / (0.2 * 0.2 / 400.0), w2 = 1.0 / (0.3 * 0.3 * 4.0 / 900.0);

	(void)state;
	assert_int_equal(stray_reduce_curve(v, 3, p, &n, &d, NULL), STRAY_OK);
	assert_int_equal(n, 2);
	assert_near(p[1].alpha, (w1 * 0.2 + w2 * 0.3) / (w1 + w2), 1e-12);
	assert_near(p[1].sigma, sqrt(1.0 / (w1 + w2)), 1e-12);
}

/* Two on-axis visits at the same place in the order: no span, no slope
 * (a rounding-level span once gave a huge one). */
static void test_curve_revisits_without_span(void **state)
{
	const struct stray_visit v[] = {
		{ 0.0, 29.5, 100.0, 1.0, 1.0, 10 },
		{ 1.0, 23.5, 40.0, 1.0, 1.0, 10 },
		{ 0.0, 29.5, 102.0, 1.0, 1.0, 10 },
	};
	struct stray_curve_point p[3];
	struct stray_drift d;
	size_t n;

	(void)state;
	assert_int_equal(stray_reduce_curve(v, 3, p, &n, &d, NULL), STRAY_OK);
	assert_false(d.fitted);
	assert_near(p[1].alpha, 40.0 / 101.0, 1e-12);
}

static void test_curve_needs_on_axis(void **state)
{
	const struct stray_visit v[] = { { 1.0, 0, 10.0, 1.0, 1.0, 10 } };
	struct stray_curve_point p[1];
	struct stray_drift d;
	struct stray_error err;
	size_t n;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_reduce_curve(v, 1, p, &n, &d, &err),
			 STRAY_ENOTFOUND);
	assert_string_equal(err.field, "ANGLE");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_curve_single_reference),
		cmocka_unit_test(test_curve_drift_line),
		cmocka_unit_test(test_curve_repeats_weighted),
		cmocka_unit_test(test_curve_revisits_without_span),
		cmocka_unit_test(test_curve_needs_on_axis),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
