/*
 * test_fdr.c - the false-detection-rate model (fdr.c, thesis eq. 2.3-2.18)
 * against closed forms written out here, tabulated normal quantiles and
 * mpmath tail values, and its properties (monotone, scaling, extensions).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../test_util.h"
#include "stray/fdr.h"

#define PI 3.14159265358979323846
#define Z95 1.6448536269514722	/* Q(Z95) = 0.05, tabulated */
#define LN_Q30 (-454.3212439563431971)	/* mpmath, tests/vectors */

/* st16-like numbers with round fluxes, independent of the photometry;
 * k_px = 1 is eq. 2.3 as the thesis prints it (test_fdr_k_px: others). */
static struct stray_fdr_model base(void)
{
	struct stray_fdr_model m = {
		.f_src_ph_s_m2 = 9e20, .f_drs_ph_s_m2 = 9e7, .t_exp_s = 0.1,
		.a_px_m2 = 2.2e-6 * 2.2e-6, .k_px = 1.0,
		.a_cs_m2 = PI * 6.5e-3 * 6.5e-3,
		.n_pps = 113.0, .n_tot = 2592.0 * 1944.0, .pr_drs = 0.95,
	};
	return m;
}

static double threshold(const struct stray_fdr_model *m)
{
	struct stray_error err;
	double i_sdt;

	stray_error_clear(&err);
	assert_int_equal(stray_fdr_threshold(m, &i_sdt, &err), STRAY_OK);
	return i_sdt;
}

static double log_rate(const struct stray_fdr_model *m, double alpha)
{
	struct stray_error err;
	double lf;

	stray_error_clear(&err);
	assert_int_equal(stray_fdr_log_rate(m, alpha, threshold(m), &lf, &err),
			 STRAY_OK);
	return lf;
}

static double alpha_req(const struct stray_fdr_model *m, double rate)
{
	struct stray_error err;
	double a;

	stray_error_clear(&err);
	assert_int_equal(stray_fdr_alpha_required(m, rate, &a, &err), STRAY_OK);
	return a;
}

/* eq. 2.3 and 2.12 as written in the thesis. */
static void test_fdr_photon_counts(void **state)
{
	struct stray_fdr_model m = base();

	(void)state;
	assert_rel(stray_fdr_pixel_photons(&m, 1e-6),
		   1e-6 * 9e20 * 0.1 * 4.84e-12, 1e-14);
	assert_rel(stray_fdr_drs_photons(&m), 9e7 * 0.1 * PI * 42.25e-6, 1e-14);
}

/* eq. 2.16: 95% of DRS stars above I_sdt = I_drs - 1.645 sqrt(I_drs). */
static void test_fdr_threshold_gaussian(void **state)
{
	struct stray_fdr_model m = base();
	double i_drs = stray_fdr_drs_photons(&m);

	(void)state;
	assert_near(threshold(&m), i_drs - Z95 * sqrt(i_drs), 1e-9);
}

/* eq. 2.17-2.18 at a moderate tail, against erfc written out here. */
static void test_fdr_rate_closed_form(void **state)
{
	struct stray_fdr_model m = base();
	double alpha = 3e-6, i_sdt = threshold(&m);
	double sigma = sqrt(m.n_pps * stray_fdr_pixel_photons(&m, alpha));
	double expect = m.n_tot / m.n_pps * 0.5 * erfc(i_sdt / sigma / sqrt(2.0));

	(void)state;
	assert_rel(exp(log_rate(&m, alpha)), expect, 1e-12);
}

/* The inverse in closed form: at FDR = R, Pr_fd = R n_pps / n_tot, so
 * sigma = I_sdt / Q^-1(Pr_fd) and alpha = sigma^2 / (n_pps F t A_px k_px). */
static double alpha_closed(const struct stray_fdr_model *m, double z)
{
	double sigma = threshold(m) / z;

	return sigma * sigma / (m->n_pps * m->f_src_ph_s_m2 * m->t_exp_s *
				m->a_px_m2 * m->k_px);
}

static void test_fdr_alpha_required_inverts_closed_form(void **state)
{
	struct stray_fdr_model m = base();
	double windows = m.n_tot / m.n_pps;

	(void)state;
	/* Pr_fd = 0.05: z = 1.6449 (tabulated) */
	assert_rel(alpha_req(&m, 0.05 * windows), alpha_closed(&m, Z95), 1e-9);
	/* Pr_fd = Q(30) ~ 5e-198: the far tail, rate ~ 2e-193 per image */
	assert_rel(alpha_req(&m, exp(LN_Q30) * windows), alpha_closed(&m, 30.0),
		   1e-9);
}

/* eq. 2.3 with the per-pixel factor of a power-ratio curve: st16-like's
 * A_cs / (n_tot A_px) = 132.7 mm^2 / 24.39 mm^2 multiplies I_px, and so
 * divides alpha_req (the closed form with k_px); the DRS (eq. 2.12) and
 * so I_sdt do not change. */
static void test_fdr_k_px(void **state)
{
	struct stray_fdr_model m = base(), t = base();
	double k = PI * 6.5 * 6.5 / (2592.0 * 1944.0 * 2.2e-3 * 2.2e-3);

	(void)state;
	m.k_px = k;
	assert_rel(stray_fdr_pixel_photons(&m, 1e-6),
		   1e-6 * 9e20 * 0.1 * 4.84e-12 * k, 1e-14);
	assert_rel(threshold(&m), threshold(&t), 1e-15);
	assert_rel(alpha_req(&m, 0.05 * m.n_tot / m.n_pps),
		   alpha_closed(&m, Z95), 1e-9);
	assert_rel(alpha_req(&t, 5.0) / alpha_req(&m, 5.0), k, 1e-8);
	assert_near(k, 5.4425, 1e-4);
}

/* Far tail: ln FDR stays exact where FDR itself underflows. */
static void test_fdr_far_tail_log_accuracy(void **state)
{
	struct stray_fdr_model m = base();
	double a = alpha_closed(&m, 30.0) ;
	double expect = log(m.n_tot / m.n_pps) + LN_Q30;

	(void)state;
	assert_near(log_rate(&m, a), expect, 1e-9);
	assert_near(log_rate(&m, alpha_closed(&m, 300.0)),
		    log(m.n_tot / m.n_pps) - 45000.0, 50.0);
}

/* FDR depends on alpha F_src only: alpha_req scales as 1 / F_src. */
static void test_fdr_alpha_required_scales_with_flux(void **state)
{
	struct stray_fdr_model sun = base(), faint = base();

	(void)state;
	faint.f_src_ph_s_m2 = sun.f_src_ph_s_m2 / 2.2e5;	/* ~ a full Moon */
	assert_rel(alpha_req(&faint, 5.0), 2.2e5 * alpha_req(&sun, 5.0), 1e-8);
}

static void assert_monotone(const struct stray_fdr_model *m)
{
	double prev = -INFINITY;
	int i;

	for (i = 0; i <= 400; i++) {
		double lf = log_rate(m, pow(10.0, -12.0 + 12.0 * i / 400.0));

		if (!(lf >= prev - 1e-12 * fabs(prev)))
			fail_msg("FDR falls from %.17g to %.17g at step %d", prev, lf, i);
		prev = lf;
	}
}

/* FDR never falls as alpha rises, in every model variant. */
static void test_fdr_monotone_in_alpha(void **state)
{
	static struct stray_region_map map = { 3, { 0.5, 0.3, 0.2 },
					       { 0.2, 1.0, 3.0 } };
	struct stray_fdr_model m = base();

	(void)state;
	assert_monotone(&m);
	m.noise = STRAY_NOISE_POISSON;
	assert_monotone(&m);
	m.read_noise_e = 3.0;
	m.dark_current_e_s = 4.0;
	assert_monotone(&m);
	m.noise = STRAY_NOISE_GAUSS;
	m.map = &map;
	assert_monotone(&m);
}

/* Exact Poisson: Pr(N >= mu + t) summed term by term for a small mean. */
static void test_fdr_poisson_exact_small_counts(void **state)
{
	struct stray_fdr_model m = base();
	struct stray_error err;
	double mu, alpha, lp, pmf, tail = 0.0;
	int k;

	(void)state;
	stray_error_clear(&err);
	m.noise = STRAY_NOISE_POISSON;
	alpha = 5.0 / (m.n_pps * stray_fdr_pixel_photons(&m, 1.0));
	mu = m.n_pps * stray_fdr_pixel_photons(&m, alpha);	/* 5 */
	assert_int_equal(stray_fdr_log_pr_fd(&m, alpha, 7.0, &lp, &err), STRAY_OK);
	for (pmf = exp(-mu), k = 0; k < 400; k++) {	/* N >= 12 */
		if (k >= 12)
			tail += pmf;
		pmf *= mu / (k + 1);
	}
	assert_rel(exp(lp), tail, 1e-11);
}

/* At large counts the Poisson and Gaussian models agree in the body. */
static void test_fdr_poisson_tends_to_gauss(void **state)
{
	struct stray_fdr_model g = base(), p = base();
	double alpha = 1e-3, lg, lp;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	p.noise = STRAY_NOISE_POISSON;
	assert_int_equal(stray_fdr_log_pr_fd(&g, alpha, 1000.0, &lg, &err), 0);
	assert_int_equal(stray_fdr_log_pr_fd(&p, alpha, 1000.0, &lp, &err), 0);
	assert_near(lp, lg, 2e-3);	/* mu ~ 5e7: z ~ 0.14 */
}

/* A one-region map is the uniform model; a half-dark detector follows
 * FDR = 0.5 n_tot/n_pps Pr_fd(2 alpha) exactly. */
static void test_fdr_region_map(void **state)
{
	static struct stray_region_map one = { 1, { 1.0 }, { 7.0 } };
	static struct stray_region_map half = { 2, { 0.5, 0.5 }, { 0.0, 1.0 } };
	struct stray_fdr_model u = base(), m = base();
	struct stray_error err;
	double alpha = 2.5e-6, lp;

	(void)state;
	stray_error_clear(&err);
	m.map = &one;
	assert_near(log_rate(&m, alpha), log_rate(&u, alpha), 1e-12);
	m.map = &half;
	assert_int_equal(stray_fdr_log_pr_fd(&u, 2.0 * alpha, threshold(&u), &lp,
					     &err), STRAY_OK);
	assert_near(log_rate(&m, alpha), log(0.5 * u.n_tot / u.n_pps) + lp, 1e-12);
	/* Concentrating the same mean light raises the FDR here. */
	assert_true(log_rate(&m, alpha) > log_rate(&u, alpha));
}

/* Detector noise widens every window: more false stars, less alpha. */
static void test_fdr_detector_noise(void **state)
{
	struct stray_fdr_model q = base(), n = base();
	struct stray_error err;
	double a;

	(void)state;
	n.read_noise_e = 3.0;
	n.dark_current_e_s = 4.0;
	assert_true(log_rate(&n, 2e-6) > log_rate(&q, 2e-6));
	assert_true(alpha_req(&n, 5.0) < alpha_req(&q, 5.0));
	/* sigma_b = sqrt(113 * 1e4) ~ 1063 e-: noise alone breaks the rate */
	n.read_noise_e = 100.0;
	stray_error_clear(&err);
	assert_int_equal(stray_fdr_alpha_required(&n, 5.0, &a, &err), STRAY_ERANGE);
	assert_string_equal(err.field, "rate");
}

static void test_fdr_rejects_bad_models(void **state)
{
	static struct stray_region_map bad_map = { 2, { 0.5, 0.6 }, { 1, 1 } };
	struct stray_fdr_model m;
	struct stray_error err;
	double v;

	(void)state;
	m = base(); m.t_exp_s = NAN; stray_error_clear(&err);
	assert_int_equal(stray_fdr_threshold(&m, &v, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "t_exp_s");
	m = base(); m.pr_drs = 1.0; stray_error_clear(&err);
	assert_int_equal(stray_fdr_threshold(&m, &v, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "pr_drs");
	m = base(); m.n_pps = 0.5; stray_error_clear(&err);
	assert_int_equal(stray_fdr_rate(&m, 1e-6, &v, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "n_pps");
	m = base(); m.k_px = 0.0; stray_error_clear(&err);
	assert_int_equal(stray_fdr_rate(&m, 1e-6, &v, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "k_px");
	m = base(); m.map = &bad_map; stray_error_clear(&err);
	assert_int_equal(stray_fdr_rate(&m, 1e-6, &v, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "map_fraction");
	m = base(); stray_error_clear(&err);
	assert_int_equal(stray_fdr_rate(&m, -1.0, &v, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "alpha");
	stray_error_clear(&err);
	assert_int_equal(stray_fdr_alpha_required(&m, 0.0, &v, &err), STRAY_EINVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fdr_photon_counts),
		cmocka_unit_test(test_fdr_threshold_gaussian),
		cmocka_unit_test(test_fdr_rate_closed_form),
		cmocka_unit_test(test_fdr_alpha_required_inverts_closed_form),
		cmocka_unit_test(test_fdr_k_px),
		cmocka_unit_test(test_fdr_far_tail_log_accuracy),
		cmocka_unit_test(test_fdr_alpha_required_scales_with_flux),
		cmocka_unit_test(test_fdr_monotone_in_alpha),
		cmocka_unit_test(test_fdr_poisson_exact_small_counts),
		cmocka_unit_test(test_fdr_poisson_tends_to_gauss),
		cmocka_unit_test(test_fdr_region_map),
		cmocka_unit_test(test_fdr_detector_noise),
		cmocka_unit_test(test_fdr_rejects_bad_models),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
