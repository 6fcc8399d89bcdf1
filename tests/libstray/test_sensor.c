/*
 * test_sensor.c - the sensor's per-pixel factor k_px of eq. 2.3
 * (sensor.c, docs/normalisation.md), derived here by counting photons,
 * not from the formula under test.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "../test_util.h"
#include "stray/sensor.h"
#include "stray/sensor_geom.h"

/* xorshift64*: uniform numbers in [0, 1), reproducible. */
static double uniform(uint64_t *s)
{
	*s ^= *s >> 12;
	*s ^= *s << 25;
	*s ^= *s >> 27;
	return (double)((*s * 2685821657736338717ull) >> 11) * 0x1.0p-53;
}

/*
 * eq. 3.11-3.12 by photon counting.  A collimated beam of photon
 * irradiance F (photons per m^2 in t_exp) falls on the aperture: photons
 * land uniformly on a square of side D around the aperture disc, and
 * those inside it are the on-axis power P(0).  Stray light of power ratio
 * alpha = P(theta)/P(0) is alpha P(0) photons spread uniformly over the
 * detector: each lands on a random pixel, and the per-pixel counts are
 * averaged.  eq. 2.3 as printed would put alpha F A_px photons in each
 * pixel; the counted mean over that is k_px.
 */
static double counted_k_px(const struct stray_sensor *s, uint64_t seed)
{
	enum { N_BEAM = 2000000 };
	static unsigned count[160 * 120];
	double d_m = s->aperture_diameter_mm * 1e-3, side_m = 1.25 * d_m;
	double f_ph_m2 = N_BEAM / (side_m * side_m), pitch_m;
	double alpha = 0.25, mean = 0.0;
	size_t n_px = (size_t)(s->pixels_x * s->pixels_y), i, in = 0, k;

	assert_true(n_px <= sizeof(count) / sizeof(count[0]));
	memset(count, 0, sizeof(count));
	for (i = 0; i < N_BEAM; i++) {	/* the on-axis beam: P(0) */
		double x = (uniform(&seed) - 0.5) * side_m;
		double y = (uniform(&seed) - 0.5) * side_m;

		in += x * x + y * y < 0.25 * d_m * d_m;
	}
	for (k = 0; k < (size_t)(alpha * in); k++)	/* alpha P(0), spread */
		count[(size_t)(uniform(&seed) * n_px)]++;
	for (i = 0; i < n_px; i++)
		mean += count[i];
	mean /= n_px;
	pitch_m = s->pixel_pitch_um * 1e-6;
	return mean / (alpha * f_ph_m2 * pitch_m * pitch_m);
}

/* A small detector, so every pixel is counted: 160 x 120 pixels of 20 um
 * behind a 5 mm aperture (A_cs / A_det = 19.6 / 7.68). */
static void test_k_px_counted_small_sensor(void **state)
{
	struct stray_sensor s = *stray_sensor_st16_like();
	double k;

	(void)state;
	s.pixels_x = 160.0;
	s.pixels_y = 120.0;
	s.pixel_pitch_um = 20.0;
	s.aperture_diameter_mm = 5.0;
	k = counted_k_px(&s, 0x9E3779B97F4A7C15ull);
	/* binomial error of P(0) (Q ~ 0.5, N 2e6): 1e-3 relative; 4 sigma */
	printf("counted k_px %.5f, stray_sensor_k_px %.5f\n", k,
	       stray_sensor_k_px(&s, STRAY_NORM_CONSISTENT));
	assert_rel(k, stray_sensor_k_px(&s, STRAY_NORM_CONSISTENT), 4e-3);
	assert_rel(k, 19.634954 / 7.68, 4e-3);
}

/* st16-like (ref4-baffle.md: 13 mm aperture, 2592 x 1944 pixels of
 * 2.2 um): 132.73 mm^2 / 24.39 mm^2 = 5.44; the thesis's is 1. */
static void test_k_px_st16_like(void **state)
{
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_fdr_model m;

	(void)state;
	assert_rel(stray_sensor_k_px(s, STRAY_NORM_CONSISTENT),
		   132.7322896 / (2592.0 * 1944.0 * 4.84e-6), 1e-8);
	assert_near(stray_sensor_k_px(s, STRAY_NORM_THESIS), 1.0, 0.0);
	stray_sensor_fdr_model(s, 1.0, 1.0, &m);	/* consistent default */
	assert_rel(m.k_px, stray_sensor_k_px(s, STRAY_NORM_CONSISTENT), 1e-15);
	assert_string_equal(stray_normalisation_name(STRAY_NORM_CONSISTENT),
			    "consistent");
	assert_string_equal(stray_normalisation_name(STRAY_NORM_THESIS),
			    "thesis");
}

/* k_px goes as d^2 / (n_tot pitch^2): geometry, not a constant. */
static void test_k_px_scaling(void **state)
{
	struct stray_sensor s = *stray_sensor_st16_like();
	double k0 = stray_sensor_k_px(&s, STRAY_NORM_CONSISTENT);

	(void)state;
	s.aperture_diameter_mm *= 2.0;
	assert_rel(stray_sensor_k_px(&s, STRAY_NORM_CONSISTENT), 4.0 * k0, 1e-12);
	s.pixels_x *= 2.0;
	assert_rel(stray_sensor_k_px(&s, STRAY_NORM_CONSISTENT), 2.0 * k0, 1e-12);
	s.pixel_pitch_um *= 2.0;
	assert_rel(stray_sensor_k_px(&s, STRAY_NORM_CONSISTENT), 0.5 * k0, 1e-12);
}

/* The ideal lens of the focal maps and frames: a ray at the field
 * half-angle lands on the detector's corner (r = f tan theta), and one
 * pitch on the axis subtends pitch / f (small angle: atan to 1e-5). */
static void test_focal_length_puts_field_edge_at_corner(void **state)
{
	struct stray_sensor s = *stray_sensor_st16_like();
	double f, corner_mm;

	(void)state;
	s.pixels_x = 100.0;
	s.pixels_y = 75.0;	/* a 3-4-5 detector: half-diagonal 62.5 px */
	s.pixel_pitch_um = 4.0;
	s.fov_half_deg = 45.0;	/* tan = 1: f is the half-diagonal */
	f = stray_sensor_focal_length_mm(&s);
	assert_near(f, 62.5 * 4e-3, 1e-12);
	s.fov_half_deg = 10.0;
	f = stray_sensor_focal_length_mm(&s);
	corner_mm = 62.5 * 4e-3;
	assert_near(atan(corner_mm / f) * 180.0 / 3.14159265358979323846, 10.0, 1e-9);
	assert_near(stray_sensor_pixel_deg(&s),
		    atan(4e-3 / f) * 180.0 / 3.14159265358979323846, 1e-5 * 4e-3 / f * 57.3);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_k_px_counted_small_sensor),
		cmocka_unit_test(test_k_px_st16_like),
		cmocka_unit_test(test_k_px_scaling),
		cmocka_unit_test(test_focal_length_puts_field_edge_at_corner),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
