/*
 * test_earth.c - the Earth quadrature against closed forms: the solid
 * angle of a cap, the irradiance of a uniform disc pi L sin^2 rho (the
 * configuration factor of a sphere; libstray's stray_earth_flux), and
 * Lambert's phase law for a distant sunlit sphere.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>

#include <cmocka.h>

#include "fdrfw/earth.h"
#include "fixture.h"
#include "stray/photometry.h"

#define PI 3.14159265358979323846
#define R_KM 6371.0088

struct sums {
	double omega, omega_cos, lambert;	/* sum w, w cos g, w cos i */
};

static void integrate(double r_km, double phase_deg, struct sums *s)
{
	/* Spacecraft on a skewed axis; the Sun at phase_deg from it as seen
	 * from the Earth's centre (phase 0: Sun behind the spacecraft). */
	double ax[3] = { 0.48, -0.6, 0.64 }, bx[3] = { 0.8, 0.0, -0.6 };
	double p = phase_deg * PI / 180.0;
	float pos[3], sun[3];
	struct fdrfw_earth_cap cap;
	unsigned k, i;

	for (i = 0; i < 3; i++) {
		pos[i] = (float)(r_km * ax[i]);
		sun[i] = (float)(cos(p) * ax[i] + sin(p) * bx[i]);
	}
	assert_int_equal(fdrfw_earth_cap(pos, sun, &cap), 1);
	s->omega = s->omega_cos = s->lambert = 0.0;
	for (k = 0; k < FDRFW_EARTH_NODES; k++) {
		struct fdrfw_earth_node n;
		double dn = 0.0, len = 0.0;

		fdrfw_earth_node(&cap, k, &n);
		for (i = 0; i < 3; i++) {
			dn += (double)n.dir[i] * (double)cap.nadir[i];
			len += (double)n.dir[i] * (double)n.dir[i];
		}
		assert_near(len, 1.0, 1e-5);
		assert_near(dn, (double)n.cos_gamma, 1e-5);
		assert_true(n.cos_sun >= 0.0f && n.cos_sun <= 1.0f + 1e-6f);
		s->omega += n.omega_sr;
		s->omega_cos += (double)n.omega_sr * n.cos_gamma;
		s->lambert += (double)n.omega_sr * n.cos_sun;
	}
}

static void test_cap_solid_angle(void **state)
{
	double alt[] = { 300.0, 550.0, 2000.0, 35786.0, 384400.0 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(alt) / sizeof(alt[0]); i++) {
		double r = R_KM + alt[i], sin_rho = R_KM / r;
		double cos_rho = sqrt(1.0 - sin_rho * sin_rho);
		double omega = 2.0 * PI * (1.0 - cos_rho);
		struct sums s;

		integrate(r, 0.0, &s);
		assert_near(s.omega, omega, 2e-4 * omega);
	}
}

/* A uniform disc of radiance L gives pi L sin^2 rho on a plane facing it;
 * with L = albedo E_sun / pi that is stray_earth_flux's albedo E sin^2 rho. */
static void test_uniform_disc_irradiance(void **state)
{
	double alt[] = { 300.0, 550.0, 2000.0, 35786.0 };
	const double f_sun = 1.0e21, albedo = 0.3;
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(alt) / sizeof(alt[0]); i++) {
		double ref, got;
		struct sums s;

		assert_int_equal(stray_earth_flux(f_sun, albedo, alt[i] * 1e3,
						  &ref, NULL), 0);
		integrate(R_KM + alt[i], 0.0, &s);
		got = albedo * f_sun / PI * s.omega_cos;
		assert_near(got, ref, 1e-4 * ref);
	}
}

/* Lambert's law for a sphere far away (Russell 1916, ApJ 43, 173): the
 * irradiance at phase angle p is (2/3) a E (R/r)^2 [sin p + (pi - p)
 * cos p] / pi.  The terminator crossing the disc is a kink the fixed
 * rule does not resolve: its error is the price of a small quadrature. */
static void test_lambert_phase_law(void **state)
{
	double r = 20000.0 * R_KM, p;

	(void)state;
	for (p = 0.0; p <= 150.0; p += 30.0) {
		double pr = p * PI / 180.0, ref, got;
		struct sums s;

		ref = 2.0 / 3.0 * (R_KM / r) * (R_KM / r) *
		      (sin(pr) + (PI - pr) * cos(pr)) / PI;
		integrate(r, p, &s);
		got = s.lambert / PI;	/* L = a E cos i / pi, a E = 1 */
		printf("lambert phase %3.0f deg: quadrature/closed form %.4f\n",
		       p, got / ref);
		assert_near(got, ref, (p < 100.0 ? 0.02 : 0.1) * ref);
	}
}

/* Sun straight behind the Earth: every visible point is in the night. */
static void test_night_side_dark(void **state)
{
	struct sums s;

	(void)state;
	integrate(R_KM + 550.0, 180.0, &s);
	assert_true(s.lambert == 0.0);
}

static void test_inside_earth_refused(void **state)
{
	float pos[3] = { 6000.0f, 0.0f, 0.0f }, sun[3] = { 1.0f, 0.0f, 0.0f };
	float nan_pos[3] = { NAN, 7000.0f, 0.0f };
	struct fdrfw_earth_cap cap;

	(void)state;
	assert_int_equal(fdrfw_earth_cap(pos, sun, &cap), 0);
	assert_int_equal(fdrfw_earth_cap(nan_pos, sun, &cap), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cap_solid_angle),
		cmocka_unit_test(test_uniform_disc_irradiance),
		cmocka_unit_test(test_lambert_phase_law),
		cmocka_unit_test(test_night_side_dark),
		cmocka_unit_test(test_inside_earth_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
