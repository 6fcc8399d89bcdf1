/*
 * test_flightcheck.c - issue 18's hidden-effect test on small frames:
 * flight frames rendered (truth.c) along an AEM sweep of the Sun offset
 * angle with a hidden scale; `stray flightcheck`'s analysis must recover
 * it within 5 % from the frames, the AEM and the catalogue alone.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mission/flightcheck_run.h"
#include "truth.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

#define N_CURVE 15

static double th[N_CURVE], al[N_CURVE];

/* A smooth decreasing system curve (the truth's and the model's shape):
 * 2e-7 at 20 deg to 2e-9 at 90 deg. */
static struct stray_curve_view curve(double floor)
{
	struct stray_curve_view v;
	int i;

	for (i = 0; i < N_CURVE; i++) {
		th[i] = 15.0 + 5.5 * i;
		al[i] = 2e-7 * pow(10.0, -(th[i] - 20.0) / 35.0) + floor;
	}
	v.n = N_CURVE;
	v.theta_deg = th;
	v.alpha = al;
	v.sigma = NULL;
	return v;
}

struct result {
	struct fc_summary s;
	struct fc_frame *f;
	size_t n;
};

/* Render, analyse against the un-floored model, summarise. */
static void run(double scale, double floor, double point_err,
		struct result *r)
{
	char dir[200], aem_path[256];
	struct fc_truth t;
	struct stray_error err = { 0 };
	struct stray_aem aem;
	struct stray_fluxes fl;
	struct fc_cfg cfg;
	struct fc_point *pts;
	struct stray_curve_view model;
	const struct stray_sensor *sn = stray_sensor_st16_like();
	size_t i;
	int rc;

	snprintf(dir, sizeof(dir), "/tmp/fc-test-%d-%g-%g", (int)getpid(), scale, floor);
	snprintf(aem_path, sizeof(aem_path), "%s.aem", dir);
	fc_truth_defaults(&t);
	t.scale = scale;
	t.point_err_arcsec = point_err;
	t.n_frames = 12;
	t.curve = curve(floor);
	assert_int_equal(fc_truth_write(&t, dir, aem_path, &err), STRAY_OK);
	assert_int_equal(stray_aem_read(aem_path, &aem, &err), STRAY_OK);
	assert_int_equal(stray_reference_fluxes(sn, &fl, &err), STRAY_OK);
	rc = fc_run_dir(dir, &aem, sn, &fl, &cfg, &r->f, &r->n, &err);
	assert_int_equal(rc, STRAY_OK);
	assert_int_equal((int)r->n, 12);
	model = curve(0.0);
	pts = calloc(r->n, sizeof(*pts));
	for (i = 0; i < r->n; i++)
		pts[i].model = stray_curve_alpha_at(&model, r->f[i].theta_deg);
	fc_summarise(&cfg, r->f, r->n,
		     stray_sensor_k_px(sn, STRAY_NORM_CONSISTENT), pts, &r->s);
	if (getenv("FC_DEBUG"))
		for (i = 0; i < r->n; i++)
			printf("# %6.2f  ratio %.4f +- %.4f  bg %.2f+-%.3f noise %.2f ncal %d\n",
			       pts[i].theta_deg, pts[i].alpha_px / pts[i].model / 5.4425,
			       pts[i].sigma / pts[i].model / 5.4425, r->f[i].bg_dn,
			       r->f[i].bg_sigma_dn, r->f[i].noise_dn, r->f[i].n_cal);
	free(pts);
	stray_aem_free(&aem);
	{
		char cmd[600];

		snprintf(cmd, sizeof(cmd), "rm -rf '%s' '%s'", dir, aem_path);
		rc = system(cmd);
	}
	(void)rc;
}

/* The Sun angles of the sweep come out of time + attitude: 20-90 deg. */
static void test_hidden_scale(void **state)
{
	struct result r;
	size_t i;
	int matched = 0;

	(void)state;
	run(1.7, 0.0, 30.0, &r);
	assert_true(fabs(r.f[0].theta_deg - 20.0) < 0.5);
	assert_true(fabs(r.f[r.n - 1].theta_deg - 90.0) < 0.5);
	for (i = 0; i < r.n; i++)
		matched += r.f[i].n_match;
	assert_true(matched >= 20);
	/* the star calibration: 1/gain DN per photo-e- (frames.h) */
	printf("# DN/e- %.4f +- %.4f (%d stars, chi2/dof %.2f); scale/k_px %.4f +- %.4f, shape chi2/dof %.2f\n",
	       r.s.dn_per_e, r.s.dn_per_e_sigma, r.s.n_cal, r.s.cal_chi2_dof,
	       r.s.scale_over_kpx, r.s.scale_over_kpx_sigma, r.s.chi2_dof);
	assert_true(fabs(r.s.dn_per_e / 0.5 - 1.0) < 0.03);
	assert_true(fabs(r.s.scale_over_kpx / 1.7 - 1.0) < 0.05);
	assert_true(fabs(r.s.scale_over_kpx - 1.7) < 3.0 * r.s.scale_over_kpx_sigma + 0.01);
	assert_true(r.s.chi2_dof < 4.0);
	free(r.f);
}

/* No hidden scale: the same analysis says the model's k_px is right. */
static void test_no_scale(void **state)
{
	struct result r;

	(void)state;
	run(1.0, 0.0, 30.0, &r);
	assert_true(fabs(r.s.scale_over_kpx - 1.0) < 0.05);
	free(r.f);
}

/* The plate solution: the AEM's pointing error (60") is found on the
 * matches and the residual is a fraction of a pixel. */
static void test_refined(void **state)
{
	struct result r;
	size_t i;
	double worst = 0.0, shift = 0.0;

	(void)state;
	run(1.7, 0.0, 60.0, &r);
	for (i = 0; i < r.n; i++) {
		if (r.f[i].n_match < 3)
			continue;
		worst = fmax(worst, r.f[i].resid_px);
		shift = fmax(shift, hypot(r.f[i].dx_px, r.f[i].dy_px));
	}
	printf("# max residual %.3f px, max shift %.2f px\n", worst, shift);
	assert_true(shift > 1.0);	/* there was an error to find */
	assert_true(worst < 0.5);
	free(r.f);
}

/* A shape the model lacks (a floor in the truth) fails the shape test. */
static void test_shape(void **state)
{
	struct result r;

	(void)state;
	run(1.7, 3e-8, 30.0, &r);
	printf("# with a hidden floor: shape chi2/dof %.1f\n", r.s.chi2_dof);
	assert_true(r.s.chi2_dof > 10.0);
	free(r.f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hidden_scale),
		cmocka_unit_test(test_no_scale),
		cmocka_unit_test(test_refined),
		cmocka_unit_test(test_shape),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
