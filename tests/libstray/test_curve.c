/*
 * test_curve.c - interpolation and exclusion angles (curve.c, thesis §5.1,
 * fig. 5.1) on curves whose crossings are known in closed form.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../test_util.h"
#include "stray/curve.h"

enum { N = 19 };

/* alpha = exp(-theta / 5) on 0..90 every 5 deg: log-linear is exact. */
static void exponential(double *th, double *al)
{
	int i;

	for (i = 0; i < N; i++) {
		th[i] = 5.0 * i;
		al[i] = exp(-th[i] / 5.0);
	}
}

static void test_curve_loglinear_interpolation_exact(void **state)
{
	double th[N], al[N];
	struct stray_curve_view c = { N, th, al, NULL };

	(void)state;
	exponential(th, al);
	assert_rel(stray_curve_alpha_at(&c, 12.3), exp(-12.3 / 5.0), 1e-13);
	assert_near(stray_curve_alpha_at(&c, -4.0), 1.0, 0.0);	/* clamped */
	assert_rel(stray_curve_alpha_at(&c, 100.0), al[N - 1], 0.0);
}

/* Crossing of alpha_req: theta = -5 ln(alpha_req). */
static void test_exclusion_monotone_closed_form(void **state)
{
	double th[N], al[N], theta;
	struct stray_curve_view c = { N, th, al, NULL };
	struct stray_error err;

	(void)state;
	exponential(th, al);
	stray_error_clear(&err);
	assert_int_equal(stray_exclusion_angle(&c, 1e-5, &theta, &err), STRAY_OK);
	assert_near(theta, -5.0 * log(1e-5), 1e-11);
}

/* A curve that dips below alpha_req and rises above it again (ref4's
 * bevel hump): the exclusion is after the last crossing, not the first. */
static void test_exclusion_after_the_last_crossing(void **state)
{
	double th[] = { 0, 10, 20, 30, 40, 50, 60 };
	double al[] = { 1, 1e-2, 1e-7, 1e-7, 1e-5, 1e-7, 1e-8 };
	struct stray_curve_view c = { 7, th, al, NULL };
	struct stray_error err;
	double theta;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_exclusion_angle(&c, 1e-6, &theta, &err), STRAY_OK);
	/* between 40 (1e-5) and 50 (1e-7): log-linear halfway */
	assert_near(theta, 45.0, 1e-12);
}

static void test_exclusion_edge_cases(void **state)
{
	double th[] = { 0, 30, 60 }, al[] = { 1e-3, 1e-4, 2e-3 };
	double zero[] = { 1, 0, 0 };
	struct stray_curve_view c = { 3, th, al, NULL }, z = { 3, th, zero, NULL };
	struct stray_error err;
	double theta = -1.0;

	(void)state;
	stray_error_clear(&err);	/* never reaches alpha_req: first angle */
	assert_int_equal(stray_exclusion_angle(&c, 1e-2, &theta, &err), STRAY_OK);
	assert_near(theta, 0.0, 0.0);
	stray_error_clear(&err);	/* ends above: not excluded */
	assert_int_equal(stray_exclusion_angle(&c, 1e-3, &theta, &err),
			 STRAY_ERANGE);
	assert_string_equal(err.field, "theta_deg");
	stray_error_clear(&err);	/* drops to exactly 0: linear crossing */
	assert_int_equal(stray_exclusion_angle(&z, 0.5, &theta, &err), STRAY_OK);
	assert_near(theta, 15.0, 1e-12);
	stray_error_clear(&err);
	assert_int_equal(stray_exclusion_angle(&c, -1.0, &theta, &err),
			 STRAY_EINVAL);
}

/* With sigma, alpha -/+ sigma give an interval around the angle; for
 * sigma = s alpha on the exponential, theta = -5 ln(alpha_req/(1 -/+ s)). */
static void test_exclusion_interval_from_sigma(void **state)
{
	double th[N], al[N], sg[N];
	struct stray_curve_view c = { N, th, al, sg };
	struct stray_exclusion ex;
	struct stray_error err;
	int i;

	(void)state;
	exponential(th, al);
	for (i = 0; i < N; i++)
		sg[i] = 0.2 * al[i];
	stray_error_clear(&err);
	assert_int_equal(stray_exclusion_interval(&c, 1e-5, 1.0, &ex, &err),
			 STRAY_OK);
	assert_true(ex.has_interval && ex.hi_reached);
	assert_near(ex.theta_deg, -5.0 * log(1e-5), 1e-11);
	assert_near(ex.theta_lo_deg, -5.0 * log(1e-5 / 0.8), 1e-11);
	assert_near(ex.theta_hi_deg, -5.0 * log(1e-5 / 1.2), 1e-11);
}

/* Issue 23: a curve that stays above alpha_req until the Sun lies in the
 * aperture plane, where a trace drops to its geometric zero, is not
 * excluded by the baffle (not 89.98 deg interpolated into that zero);
 * cut at 89 deg it says the same; where the curve itself falls below
 * before 90 deg, that crossing. */
static void test_exclusion_not_by_the_aperture_plane(void **state)
{
	double th[] = { 0, 30, 60, 89, 90 }, al[] = { 1, 1e-4, 5e-7, 4.8e-7, 0 };
	double th2[] = { 0, 30, 60, 89, 89.5, 90 };
	double al2[] = { 1, 1e-4, 5e-7, 4.8e-7, 1e-8, 0 };
	struct stray_curve_view c = { 5, th, al, NULL }, cut = { 4, th, al, NULL },
				ok = { 6, th2, al2, NULL };
	struct stray_exclusion ex;
	struct stray_error err;
	double theta = -1.0;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_exclusion_angle(&c, 6.45e-8, &theta, &err),
			 STRAY_ERANGE);
	assert_int_equal(stray_exclusion_interval(&c, 6.45e-8, 1.0, &ex, &err),
			 STRAY_OK);
	assert_false(ex.excluded);
	assert_true(isnan(ex.theta_deg));
	assert_string_equal(ex.reason, STRAY_EXCL_PLANE_ONLY);
	assert_near(ex.last_above_deg, 89.0, 0.0);
	assert_int_equal(stray_exclusion_interval(&cut, 6.45e-8, 1.0, &ex, &err),
			 STRAY_OK);
	assert_false(ex.excluded);
	assert_string_equal(ex.reason, STRAY_EXCL_ENDS_ABOVE);
	assert_int_equal(stray_exclusion_interval(&ok, 6.45e-8, 1.0, &ex, &err),
			 STRAY_OK);
	assert_true(ex.excluded && ex.reason == NULL);
	assert_true(ex.theta_deg > 89.0 && ex.theta_deg < 89.5);
}

static void test_curve_check_rejects_bad_curves(void **state)
{
	double th[] = { 0, 10, 10 }, al[] = { 1, 0.5, 0.1 };
	double th2[] = { 0, 10, 20 }, al2[] = { 1, NAN, 0.1 }, sg2[] = { 0, -1, 0 };
	struct stray_curve_view dup = { 3, th, al, NULL },
				nan_alpha = { 3, th2, al2, NULL },
				neg_sigma = { 3, th2, al, sg2 };
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_curve_check(&dup, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "theta_deg");
	stray_error_clear(&err);
	assert_int_equal(stray_curve_check(&nan_alpha, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "alpha");
	stray_error_clear(&err);
	assert_int_equal(stray_curve_check(&neg_sigma, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "sigma");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_curve_loglinear_interpolation_exact),
		cmocka_unit_test(test_exclusion_monotone_closed_form),
		cmocka_unit_test(test_exclusion_after_the_last_crossing),
		cmocka_unit_test(test_exclusion_edge_cases),
		cmocka_unit_test(test_exclusion_interval_from_sigma),
		cmocka_unit_test(test_exclusion_not_by_the_aperture_plane),
		cmocka_unit_test(test_curve_check_rejects_bad_curves),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
