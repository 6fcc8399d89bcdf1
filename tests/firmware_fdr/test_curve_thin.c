/*
 * test_curve_thin.c - a curve longer than the flight table's 128 rows
 * thinned to them (firmware_fdr/ground/curve_thin.c): a curve that fits
 * is untouched; a 400-row curve keeps its ends and 128 rows, the error it
 * reports is the largest left-out error recomputed here by hand, and the
 * two samples around a crossing asked for are kept, so the exclusion
 * angle of the thinned curve is the whole curve's.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../test_util.h"
#include "fdrfw/table_build.h"
#include "stray/curve.h"

#define N 400

static double th[N], al[N];

/* A baffle-like curve: direct light to 20 deg, then scatter falling
 * 6 decades with a ripple, 0 at 90 deg. */
static struct stray_curve_view curve(void)
{
	struct stray_curve_view v = { N, th, al, NULL };
	int i;

	for (i = 0; i < N; i++) {
		th[i] = 90.0 * i / (N - 1);
		al[i] = th[i] < 20.0 ? cos(th[i] * 0.0174532925) *
			(1.0 - th[i] / 20.0) + 1e-3 :
			pow(10.0, -3.0 - 6.0 * (th[i] - 20.0) / 70.0 +
			    0.3 * sin(th[i]));
	}
	al[N - 1] = 0.0;
	return v;
}

static double lg(double a)
{
	return a > 0.0 ? fmax(log10(a), (double)FDRFW_LOG10_ALPHA_FLOOR)
		       : (double)FDRFW_LOG10_ALPHA_FLOOR;
}

static void test_fits_untouched(void **state)
{
	static double t2[FDRFW_CURVE_MAX], a2[FDRFW_CURVE_MAX];
	struct stray_curve_view v = curve(), out;
	struct fdrfw_thin_report r;

	(void)state;
	v.n = 100;
	assert_int_equal(fdrfw_curve_thin(&v, NULL, 0, t2, a2, &out, &r,
					  NULL), 0);
	assert_ptr_equal(out.theta_deg, th);
	assert_int_equal(r.rows_out, 100);
	assert_true(isnan(r.at_deg));
}

static void test_thinned_error_and_crossing(void **state)
{
	static double t2[FDRFW_CURVE_MAX], a2[FDRFW_CURVE_MAX];
	struct stray_curve_view v = curve(), out;
	struct fdrfw_thin_report r;
	double req = 3.3e-6, whole, thin, worst = 0.0;
	size_t i, k = 0;

	(void)state;
	assert_int_equal(fdrfw_curve_thin(&v, &req, 1, t2, a2, &out, &r,
					  NULL), 0);
	assert_int_equal(out.n, FDRFW_CURVE_MAX);
	assert_int_equal(r.rows_in, N);
	assert_near(out.theta_deg[0], 0.0, 0.0);
	assert_near(out.theta_deg[out.n - 1], 90.0, 0.0);
	/* every left-out sample against the line of its kept neighbours */
	for (i = 0; i < N; i++) {
		double f, e;

		while (k + 1 < out.n && out.theta_deg[k + 1] <= th[i])
			k++;
		if (out.theta_deg[k] == th[i] || k + 1 >= out.n)
			continue;
		f = (th[i] - out.theta_deg[k]) /
		    (out.theta_deg[k + 1] - out.theta_deg[k]);
		e = fabs(lg(al[i]) - (lg(out.alpha[k]) +
			 f * (lg(out.alpha[k + 1]) - lg(out.alpha[k]))));
		worst = fmax(worst, e);
	}
	assert_near(r.max_err_dex, worst, 1e-12);
	assert_true(worst < 0.05);
	/* the crossing from the same two samples: the same angle */
	assert_int_equal(stray_exclusion_angle(&v, req, &whole, NULL), 0);
	assert_int_equal(stray_exclusion_angle(&out, req, &thin, NULL), 0);
	assert_near(thin, whole, 1e-9);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fits_untouched),
		cmocka_unit_test(test_thinned_error_and_crossing),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
