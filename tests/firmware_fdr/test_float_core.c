/*
 * test_float_core.c - libstray's core built with STRAY_REAL_FLOAT (the
 * flight build's option) run on the host beside the double core and
 * compared call for call, and against mpmath's tail values.
 *
 * Tolerances come from float's epsilon (6e-8), not from what the code
 * happens to give: ln Q(z) to 8 eps relative (z^2/2 is formed in float),
 * z = Q^-1(p) to Brent's float tolerance plus the residual's rounding,
 * ln FDR to the 1e-3 wherever FDR >= 1e-30 (the flight vectors'
 * criterion) and 8 eps relative below.
 */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "fixture.h"
#include "fdrfw/model_map.h"
#include "float_core.h"
#include "stray/fdr.h"
#include "stray/table.h"
#include "stray/tail.h"

#define EPS_F ((double)FLT_EPSILON)
#define LN_FDR_FLOOR (-69.07755278982137)	/* ln 1e-30 */

/* The flight table's model, through the module's mapping in both cores:
 * the same float inputs reach both.  The table outlives the calls. */
static void models(double t_exp_s, struct fcore_model *f,
		   struct stray_fdr_model *d)
{
	static struct fdrfw_table t;

	fixture_table(&t);
	*f = (struct fcore_model){ &t, t_exp_s, (double)t.f_sun_ph_s_m2 };
	fdrfw_model_from_table(&t, d);
	d->t_exp_s = f->t_exp_s;
	d->f_src_ph_s_m2 = f->f_src_ph_s_m2;
}

/* The option took effect: the object really computes in float. */
static void test_built_as_float(void **state)
{
	double v;

	(void)state;
	assert_true(fcore_real_is_float());
	/* Its results are floats: ln Q(1) = -1.841... is not one in double. */
	v = fcore_log_gauss_q(1.0);
	assert_true((double)(float)v == v);
	assert_true(stray_log_gauss_q(1.0) != v);
}

/* eq. 2.17 kernel against mpmath (60 digits), z in [-30, 1000]. */
static void test_log_gauss_q_vs_mpmath(void **state)
{
	struct stray_table t;
	struct stray_error err;
	double worst = 0.0;
	size_t i;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_table_read("tests/vectors/gauss_tail.csv", &t,
					  &err), STRAY_OK);
	for (i = 0; i < t.n_rows; i++) {
		double z = t.cell[3 * i], ref = t.cell[3 * i + 1];
		double got = fcore_log_gauss_q(z);
		double tol = 1e-6 + 8.0 * EPS_F * fabs(ref);

		if (!(fabs(got - ref) <= tol))
			fail_msg("z = %g: float ln Q = %.9g, mpmath %.17g", z,
				 got, ref);
		worst = fmax(worst, fabs(got - ref) / (1.0 + fabs(ref)));
	}
	stray_table_free(&t);
	print_message("float ln Q vs mpmath: worst |d| / (1 + |ln Q|) %.3g\n",
		      worst);
}

/* The same kernel on a dense grid against the double core, z as float. */
static void test_log_gauss_q_vs_double(void **state)
{
	int k;

	(void)state;
	for (k = -3000; k <= 4500; k++) {
		double z = (double)(float)(k * 0.01);
		double d = stray_log_gauss_q(z), f = fcore_log_gauss_q(z);

		if (!(fabs(f - d) <= 1e-6 + 8.0 * EPS_F * fabs(d)))
			fail_msg("z = %.9g: float %.9g, double %.17g", z, f, d);
	}
}

/* Q^-1 by Brent in float: z within the scaled tolerance (5.4e-6) plus the
 * residual's rounding, eps |ln p| / |d ln Q / dz| <= eps |ln p|. */
static void test_q_inv_vs_double(void **state)
{
	int k;

	(void)state;
	for (k = 1; k <= 74; k++) {
		double p = k <= 37 ? pow(10.0, -k) : (double)(k - 37) / 38.0;
		double zd, zf;

		p = (double)(float)p;
		assert_int_equal(stray_gauss_q_inv(p, &zd, NULL), STRAY_OK);
		assert_int_equal(fcore_gauss_q_inv(p, &zf), STRAY_OK);
		if (!(fabs(zf - zd) <= 1e-5 + 4.0 * EPS_F * fabs(log(p))))
			fail_msg("p = %g: float z %.9g, double %.17g", p,
				 zf, zd);
	}
}

/* Brent's bracket and bounded iterations hold in float (cbrt). */
static void test_brent_in_float(void **state)
{
	int k;

	(void)state;
	for (k = 1; k <= 1000; k += 37) {
		double x, root = cbrt((double)k);
		int it;

		assert_int_equal(fcore_root_cbrt((double)k, &x, &it), STRAY_OK);
		if (!(fabs(x - root) <= 4.0 * EPS_F * root + 5.4e-6))
			fail_msg("cbrt(%d): float %.9g, exact %.17g", k, x,
				 root);
		assert_true(it <= 60);
	}
}

/* eq. 2.16-2.18 end to end: threshold, then ln FDR over alpha from the
 * far tail (ln FDR ~ -800) to saturation, at three exposures. */
static void test_fdr_vs_double(void **state)
{
	static const double t_exp[] = { 0.02, 0.1, 0.5 };
	double worst = 0.0;
	size_t e;

	(void)state;
	for (e = 0; e < sizeof(t_exp) / sizeof(t_exp[0]); e++) {
		struct fcore_model fm;
		struct stray_fdr_model dm;
		double id, ifl;
		int k;

		models(t_exp[e], &fm, &dm);
		assert_int_equal(stray_fdr_threshold(&dm, &id, NULL), STRAY_OK);
		assert_int_equal(fcore_fdr_threshold(&fm, &ifl), STRAY_OK);
		assert_true(fabs(ifl - id) <= 4.0 * EPS_F * id);
		for (k = -160; k <= 16; k++) {
			double alpha = pow(10.0, k / 8.0), ld, lf, tol;

			alpha = (double)(float)alpha;
			assert_int_equal(stray_fdr_log_rate(&dm, alpha, id, &ld,
							    NULL), STRAY_OK);
			assert_int_equal(fcore_fdr_log_rate(&fm, alpha, ifl,
							    &lf), STRAY_OK);
			tol = ld >= LN_FDR_FLOOR ? 1e-3 :
			      1e-3 + 8.0 * EPS_F * fabs(ld);
			if (!(fabs(lf - ld) <= tol))
				fail_msg("t %g alpha %g: float ln FDR %.9g, "
					 "double %.17g", t_exp[e], alpha, lf,
					 ld);
			if (ld >= LN_FDR_FLOOR)
				worst = fmax(worst, fabs(lf - ld));
		}
	}
	print_message("float ln FDR vs double where FDR >= 1e-30: worst %.3g\n",
		      worst);
}

/* The closed-form threshold the module uses after an exposure change is
 * stray_fdr_threshold's own expression, with z solved once. */
static void test_threshold_closed_form(void **state)
{
	struct fcore_model fm;
	struct stray_fdr_model dm;
	double z, i_full, i_closed;

	(void)state;
	models(0.25, &fm, &dm);
	assert_int_equal(fcore_gauss_q_inv(dm.pr_drs, &z), STRAY_OK);
	assert_int_equal(fcore_fdr_threshold(&fm, &i_full), STRAY_OK);
	i_closed = fcore_fdr_threshold_gauss(&fm, z);
	assert_true(i_closed == i_full);
}

/* fig. 2.7's inversion: alpha_req to the float search's tolerance on ln
 * alpha (5.4e-4) plus ln FDR's rounding over its slope. */
static void test_alpha_required_vs_double(void **state)
{
	static const double rate[] = { 1e-4, 0.01, 1.0, 5.0 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(rate) / sizeof(rate[0]); i++) {
		struct fcore_model fm;
		struct stray_fdr_model dm;
		double ad, af;

		models(0.1, &fm, &dm);
		assert_int_equal(stray_fdr_alpha_required(&dm, rate[i], &ad,
							  NULL), STRAY_OK);
		assert_int_equal(fcore_fdr_alpha_required(&fm, rate[i], &af),
				 STRAY_OK);
		if (!(fabs(log(af / ad)) <= 1e-3))
			fail_msg("rate %g: float alpha_req %.9g, double %.17g",
				 rate[i], af, ad);
	}
}

/* The Poisson tail (built in on the host's float core): ln P(a, x) by
 * series and continued fraction against the double core. */
static void test_log_gamma_p_vs_double(void **state)
{
	static const double ax[][2] = { { 1, 0.5 }, { 3, 1 }, { 10, 3 },
		{ 10, 20 }, { 30, 10 }, { 50, 80 }, { 100, 60 }, { 200, 150 } };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(ax) / sizeof(ax[0]); i++) {
		double d, f;

		assert_int_equal(stray_log_gamma_p(ax[i][0], ax[i][1], &d,
						   NULL), STRAY_OK);
		assert_int_equal(fcore_log_gamma_p(ax[i][0], ax[i][1], &f),
				 STRAY_OK);
		/* a ln x - x - ln Gamma(a): terms of size ~a ln a cancel. */
		if (!(fabs(f - d) <= 1e-5 + 16.0 * EPS_F * ax[i][0] *
				      (1.0 + log(ax[i][0]))))
			fail_msg("a %g x %g: float ln P %.9g, double %.17g",
				 ax[i][0], ax[i][1], f, d);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_built_as_float),
		cmocka_unit_test(test_log_gauss_q_vs_mpmath),
		cmocka_unit_test(test_log_gauss_q_vs_double),
		cmocka_unit_test(test_q_inv_vs_double),
		cmocka_unit_test(test_brent_in_float),
		cmocka_unit_test(test_fdr_vs_double),
		cmocka_unit_test(test_threshold_closed_form),
		cmocka_unit_test(test_alpha_required_vs_double),
		cmocka_unit_test(test_log_gamma_p_vs_double),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
