/*
 * test_photometry.c - eq. 2.1-2.2 (photometry.c) against Planck's law in
 * closed form, exact polynomial integrals, and an independent fine-grid
 * integration of the shipped spectra.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <cmocka.h>

#include "../test_util.h"
#include "stray/photometry.h"
#include "stray/photometry_io.h"
#include "stray/spectrum_io.h"

#define HC (STRAY_PLANCK_J_S * STRAY_LIGHT_SPEED_M_S)

static double flux_of(const struct stray_spectrum *f,
		      const struct stray_spectrum *s)
{
	struct stray_error err;
	double v;

	stray_error_clear(&err);
	assert_int_equal(stray_photon_flux(f, s, &v, &err), STRAY_OK);
	return v;
}

/* Planck photon radiance in a band, in closed form:
 * int B_l l/(hc) dl = 2 c (kT/hc)^3 int x^2/(e^x - 1) dx, x = hc/(l k T),
 * and int_x^inf x^2/(e^x-1) = sum_n e^-nx (x^2/n + 2x/n^2 + 2/n^3). */
static double planck_tail(double x)
{
	double s = 0.0;
	int n;

	for (n = 1; n < 2000; n++)
		s += exp(-n * x) * (x * x / n + 2.0 * x / ((double)n * n) +
				    2.0 / ((double)n * n * n));
	return s;
}

static void test_photon_flux_blackbody_closed_form(void **state)
{
	const double T = 5778.0, kT = STRAY_BOLTZMANN_J_K * T;
	enum { N = 3201 };	/* 300..1100 nm every 0.25 nm */
	double *wl = malloc(N * sizeof(double)), *b = malloc(N * sizeof(double));
	double band_wl[2] = { 400.0, 900.0 }, band_v[2] = { 1.0, 1.0 };
	double x_lo, x_hi, expect;
	int i;

	(void)state;
	for (i = 0; i < N; i++) {
		double l = (300.0 + 0.25 * i) * 1e-9;

		wl[i] = 300.0 + 0.25 * i;
		/* B_l [W m^-2 sr^-1 m^-1] -> per nm */
		b[i] = 2.0 * HC * STRAY_LIGHT_SPEED_M_S / pow(l, 5) /
		       expm1(HC / (l * kT)) * 1e-9;
	}
	{
		struct stray_spectrum f = { N, wl, b }, s = { 2, band_wl, band_v };

		x_lo = HC / (900e-9 * kT);
		x_hi = HC / (400e-9 * kT);
		expect = 2.0 * STRAY_LIGHT_SPEED_M_S * pow(kT / HC, 3) *
			 (planck_tail(x_lo) - planck_tail(x_hi));
		assert_rel(flux_of(&f, &s), expect, 2e-6);
	}
	free(wl);
	free(b);
}

/* The integrand of two piecewise-linear curves times lambda is cubic, so
 * the union-grid Simpson sum is exact: compare with the polynomial
 * integral of (a + b l)(c + d l) l done by hand on each piece. */
static double cubic_integral(double a, double b, double c, double d,
			     double x0, double x1)
{
	/* (a + b l)(c + d l) l = ac l + (ad + bc) l^2 + bd l^3 */
#define P(x) (a * c * (x) * (x) / 2 + (a * d + b * c) * pow(x, 3) / 3 + \
	      b * d * pow(x, 4) / 4)
	return P(x1) - P(x0);
#undef P
}

static void test_photon_flux_exact_on_union_grid(void **state)
{
	double fw[] = { 500.0, 600.0 }, fv[] = { 1.0, 3.0 };
	double sw[] = { 520.0, 550.0, 580.0 }, sv[] = { 0.2, 0.8, 0.5 };
	struct stray_spectrum f = { 2, fw, fv }, s = { 3, sw, sv };
	/* f = 1 + (l - 500)/50 = -9 + l/50 */
	double expect = cubic_integral(-9.0, 1.0 / 50, 0.2 - 520.0 * 0.02, 0.02,
				       520.0, 550.0) +
			cubic_integral(-9.0, 1.0 / 50, 0.8 + 550.0 * 0.01, -0.01,
				       550.0, 580.0);

	(void)state;
	assert_rel(flux_of(&f, &s), expect * 1e-9 / HC, 1e-13);
	/* Swapping the roles changes nothing. */
	assert_rel(flux_of(&s, &f), expect * 1e-9 / HC, 1e-13);
}

/* Curves that do not overlap give exactly zero. */
static void test_photon_flux_zero_outside_support(void **state)
{
	double fw[] = { 300.0, 400.0 }, fv[] = { 1.0, 1.0 };
	double sw[] = { 400.5, 500.0 }, sv[] = { 1.0, 1.0 };
	struct stray_spectrum f = { 2, fw, fv }, s = { 2, sw, sv };

	(void)state;
	assert_true(flux_of(&f, &s) == 0.0);
	assert_true(stray_spectrum_at(&s, 400.4) == 0.0);
	assert_near(stray_spectrum_at(&s, 400.5), 1.0, 0.0);
}

static void test_spectrum_check_rejects_bad_samples(void **state)
{
	double w1[] = { 500.0, 500.0, 600.0 }, v1[] = { 1, 1, 1 };
	double w2[] = { 500.0, 550.0, 600.0 }, v2[] = { 1, -1e-3, 1 };
	double w3[] = { 500.0, 550.0, 600.0 }, v3[] = { 1, NAN, 1 };
	struct stray_spectrum s1 = { 3, w1, v1 }, s2 = { 3, w2, v2 },
			      s3 = { 3, w3, v3 };
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_spectrum_check(&s1, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "wavelength_nm");
	stray_error_clear(&err);
	assert_int_equal(stray_spectrum_check(&s2, &err), STRAY_EINVAL);
	assert_near(err.value, -1e-3, 0.0);
	stray_error_clear(&err);
	assert_int_equal(stray_spectrum_check(&s3, &err), STRAY_EINVAL);
}

/* eq. 2.2 both ways; 5 magnitudes are a factor of 100 exactly. */
static void test_magnitudes_round_trip(void **state)
{
	double f0 = stray_zero_mag_flux(1.7e10, 0.03), m;

	(void)state;
	assert_near(stray_flux_to_mag(f0, 1.7e10), 0.03, 1e-13);
	for (m = -27.0; m <= 20.0; m += 0.37)
		assert_near(stray_flux_to_mag(f0, stray_mag_to_flux(f0, m)), m,
			    1e-12);
	assert_rel(stray_mag_to_flux(f0, 1.3) / stray_mag_to_flux(f0, 6.3),
		   100.0, 1e-13);
}

static void test_moon_phase_law(void **state)
{
	(void)state;
	assert_near(stray_moon_mag_at_phase(-12.6, 0.0), -12.6, 0.0);
	assert_near(stray_moon_mag_at_phase(-12.6, 90.0),
		    -12.6 + 2.34 + 4e-9 * 65610000.0, 1e-12);
	assert_near(stray_moon_mag_at_phase(-12.6, -90.0),
		    stray_moon_mag_at_phase(-12.6, 90.0), 0.0);
}

/* A disc of uniform radiance L fills half-angle rho: E = pi L sin^2 rho.
 * At altitude R the Earth's rho is 30 deg, so E = albedo E_sun / 4. */
static void test_earth_flux_disc_irradiance(void **state)
{
	struct stray_error err;
	double f;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_earth_flux(8e20, 0.3, STRAY_EARTH_RADIUS_M, &f,
					  &err), STRAY_OK);
	assert_rel(f, 0.3 * 8e20 / 4.0, 1e-14);
	assert_int_equal(stray_earth_flux(8e20, 1.5, 5e5, &f, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "albedo");
}

/* An independent integration of the shipped spectra: both curves sampled
 * on a uniform 0.005 nm grid by their own interpolation, trapezoid rule. */
static double fine_flux(const struct stray_spectrum *f,
			const struct stray_spectrum *s)
{
	double lo = fmax(f->wavelength_nm[0], s->wavelength_nm[0]);
	double hi = fmin(f->wavelength_nm[f->n - 1], s->wavelength_nm[s->n - 1]);
	double h = 0.005, sum = 0.0, prev = 0.0, l;
	size_t i = 0, j = 0;
	long k, n = (long)((hi - lo) / h);

	for (k = 0; k <= n; k++) {
		double a, b, g;

		l = k == n ? hi : lo + k * h;
		while (i + 2 < f->n && f->wavelength_nm[i + 1] < l)
			i++;
		while (j + 2 < s->n && s->wavelength_nm[j + 1] < l)
			j++;
		a = f->value[i] + (f->value[i + 1] - f->value[i]) *
			(l - f->wavelength_nm[i]) /
			(f->wavelength_nm[i + 1] - f->wavelength_nm[i]);
		b = s->value[j] + (s->value[j + 1] - s->value[j]) *
			(l - s->wavelength_nm[j]) /
			(s->wavelength_nm[j + 1] - s->wavelength_nm[j]);
		g = a * b * l * 1e-9 / HC;
		if (k > 0)
			sum += 0.5 * (g + prev) * (k == n ? hi - (lo + (n - 1) * h) : h);
		prev = g;
	}
	return sum;
}

static void test_reference_fluxes_match_fine_grid(void **state)
{
	const struct stray_sensor *st16 = stray_sensor_st16_like();
	struct stray_spectrum_data sun, vega, qe;
	struct stray_fluxes f;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_reference_fluxes(st16, &f, &err), STRAY_OK);
	assert_int_equal(stray_spectrum_load(st16->sun, &sun, &err), STRAY_OK);
	assert_int_equal(stray_spectrum_load(st16->vega, &vega, &err), STRAY_OK);
	assert_int_equal(stray_spectrum_load(st16->qe, &qe, &err), STRAY_OK);
	assert_rel(f.sun, fine_flux(&sun.s, &qe.s), 1e-5);
	assert_rel(f.vega, fine_flux(&vega.s, &qe.s), 1e-5);
	/* eq. 2.2 chain: F_0 from Vega at 0.03, DRS at 5.75, Moon at -12.6 */
	assert_rel(f.zero_mag, f.vega * pow(10.0, 0.4 * 0.03), 1e-14);
	assert_rel(f.drs, f.zero_mag * pow(10.0, -0.4 * 5.75), 1e-14);
	assert_rel(f.moon, f.zero_mag * pow(10.0, 0.4 * 12.6), 1e-14);
	/* The Sun is ~ -26.7 in V; in this red-sensitive band about the same */
	assert_true(f.sun_mag > -27.2 && f.sun_mag < -26.4);
	stray_spectrum_data_free(&sun);
	stray_spectrum_data_free(&vega);
	stray_spectrum_data_free(&qe);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_photon_flux_blackbody_closed_form),
		cmocka_unit_test(test_photon_flux_exact_on_union_grid),
		cmocka_unit_test(test_photon_flux_zero_outside_support),
		cmocka_unit_test(test_spectrum_check_rejects_bad_samples),
		cmocka_unit_test(test_magnitudes_round_trip),
		cmocka_unit_test(test_moon_phase_law),
		cmocka_unit_test(test_earth_flux_disc_irradiance),
		cmocka_unit_test(test_reference_fluxes_match_fine_grid),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
