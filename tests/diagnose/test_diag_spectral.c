/*
 * test_diag_spectral.c - issue 17 item 5: the coating is two-band, dark
 * in the blue (rho 0.02 below 650 nm) and brighter in the red (0.10
 * above), weighted by the Sun x QE band photon by photon in the truth
 * generator; the model is grey.  The diagnosis must name spectral_slope
 * (not a grey reflectance) with a slope whose interval excludes 0, cut
 * the RMS log residual, and its fitted coating must carry the truth's
 * band moments <rho> and <rho^2> / <rho>^2 (what single- and
 * double-scatter paths see) within 15 %.  The sign of the slope is not
 * asserted: a k-scatter path sees only <rho^k> over the band, i.e. the
 * distribution of rho(l) under the band's weights, which a power law
 * can match from either side (dark where the band is heavy, bright in
 * its minority tail); a second band (another response) would tell.
 */
#include "diag_test.h"
#include "diagnose/diag_spectral.h"

static void test_two_band_coating(void **state)
{
	struct truth_config c;
	const cJSON *sp;
	cJSON *j;
	int inside = 0;
	double s, rho0, m[3], f[3];

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.band_rho_blue = 0.02;
	c.band_rho_red = 0.10;
	c.band_split_nm = 650.0;
	c.n_paths = 500000;
	j = diagnose_truth(&c);
	show(__func__, j);
	sp = cause(j, "spectral_slope");
	assert_true(flag(j, "significant"));
	assert_non_null(sp);
	assert_null(cause(j, "reflectance"));
	s = param(sp, "slope", 0.0, &inside);
	assert_false(inside);		/* 0 (grey) outside the interval */
	assert_int_equal(truth_band_moments(&c, m, 2), 0);
	rho0 = param(sp, "reflectance", m[1], &inside);	/* band mean, shown */
	diag_band_moments(diag_band_current(), rho0, s, f, 2);
	fprintf(stderr, "  <rho> %.4f fitted %.4f; <rho^2>/<rho>^2 %.3f "
		"fitted %.3f\n", m[1], f[1], m[2] / (m[1] * m[1]),
		f[2] / (f[1] * f[1]));
	assert_true(fabs(f[1] / m[1] - 1.0) < 0.15);
	assert_true(fabs(f[2] / (f[1] * f[1]) / (m[2] / (m[1] * m[1])) - 1.0)
		    < 0.15);
	assert_true(num(j, "rms_before") >= 2.0 * num(j, "rms_after"));
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_band_coating),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
