/*
 * photometry.c - photon flux in a passband and magnitudes (thesis §2.1,
 * eq. 2.1-2.2).  Freestanding.
 */
#include <math.h>

#include "stray/config.h"
#include "stray/photometry.h"

int stray_spectrum_check(const struct stray_spectrum *s,
			 struct stray_error *err)
{
	size_t i;

	if (s->n < 2)
		return stray_error_set_value(err, STRAY_EINVAL, "wavelength_nm",
			STRAY_MSG("a spectrum needs at least 2 samples"),
			(double)s->n);
	for (i = 0; i < s->n; i++) {
		double w = s->wavelength_nm[i], v = s->value[i];

		if (!(isfinite(w) && w > 0.0))
			return stray_error_set_value(err, STRAY_EINVAL,
				"wavelength_nm", STRAY_MSG("must be finite and > 0"),
				w);
		if (i > 0 && !(w > s->wavelength_nm[i - 1]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"wavelength_nm",
				STRAY_MSG("must be strictly increasing"), w);
		if (!(isfinite(v) && v >= 0.0))
			return stray_error_set_value(err, STRAY_EINVAL, "value",
				STRAY_MSG("must be finite and >= 0"), v);
	}
	return STRAY_OK;
}

/* Value of segment k's line (between samples k and k+1) at x. */
static double segment_at(const struct stray_spectrum *s, size_t k, double x)
{
	double x0 = s->wavelength_nm[k], x1 = s->wavelength_nm[k + 1];
	double t = (x - x0) / (x1 - x0);

	return s->value[k] + t * (s->value[k + 1] - s->value[k]);
}

double stray_spectrum_at(const struct stray_spectrum *s, double lambda_nm)
{
	size_t lo = 0, hi = s->n - 1;

	if (!(lambda_nm >= s->wavelength_nm[0] && lambda_nm <= s->wavelength_nm[hi]))
		return 0.0;
	while (hi - lo > 1) {
		size_t mid = lo + (hi - lo) / 2;

		if (s->wavelength_nm[mid] <= lambda_nm)
			lo = mid;
		else
			hi = mid;
	}
	return segment_at(s, lo, lambda_nm);
}

/* Advance segment cursor k of s so that x lies in [w_k, w_k+1). */
static size_t segment_of(const struct stray_spectrum *s, size_t k, double x)
{
	while (k + 2 < s->n && s->wavelength_nm[k + 1] <= x)
		k++;
	return k;
}

/* The integrand of eq. 2.1 without 1/(h c): f(l) S(l) l, l in nm. */
static double integrand(const struct stray_spectrum *f, size_t kf,
			const struct stray_spectrum *s, size_t ks, double x)
{
	return segment_at(f, kf, x) * segment_at(s, ks, x) * x;
}

int stray_photon_flux(const struct stray_spectrum *irradiance,
		      const struct stray_spectrum *response,
		      double *flux_ph_s_m2, struct stray_error *err)
{
	const struct stray_spectrum *f = irradiance, *s = response;
	double lo, hi, x, sum = 0.0;
	size_t kf = 0, ks = 0, i = 0, j = 0;
	int rc;

	if ((rc = stray_spectrum_check(f, err)) != STRAY_OK ||
	    (rc = stray_spectrum_check(s, err)) != STRAY_OK)
		return rc;
	/* Zero outside either support: integrate over their intersection. */
	lo = fmax(f->wavelength_nm[0], s->wavelength_nm[0]);
	hi = fmin(f->wavelength_nm[f->n - 1], s->wavelength_nm[s->n - 1]);
	x = lo;
	/* Walk the union grid; each step ends at the next sample of either. */
	while (x < hi) {
		double next = hi, mid, a, m, b;

		while (i < f->n && f->wavelength_nm[i] <= x)
			i++;
		while (j < s->n && s->wavelength_nm[j] <= x)
			j++;
		if (i < f->n && f->wavelength_nm[i] < next)
			next = f->wavelength_nm[i];
		if (j < s->n && s->wavelength_nm[j] < next)
			next = s->wavelength_nm[j];
		mid = 0.5 * (x + next);
		kf = segment_of(f, kf, mid);
		ks = segment_of(s, ks, mid);
		a = integrand(f, kf, s, ks, x);
		m = integrand(f, kf, s, ks, mid);
		b = integrand(f, kf, s, ks, next);
		/* Simpson: exact for the cubic on this interval. */
		sum += (next - x) / 6.0 * (a + 4.0 * m + b);
		x = next;
	}
	/* eq. 2.1: lambda [nm -> m] / (h c); d lambda stays in nm. */
	*flux_ph_s_m2 = sum * 1e-9 / (STRAY_PLANCK_J_S * STRAY_LIGHT_SPEED_M_S);
	return STRAY_OK;
}

double stray_zero_mag_flux(double f_ref_ph_s_m2, double m_ref)
{
	return f_ref_ph_s_m2 * pow(10.0, 0.4 * m_ref);
}

double stray_mag_to_flux(double f0_ph_s_m2, double mag)
{
	return f0_ph_s_m2 * pow(10.0, -0.4 * mag);
}

double stray_flux_to_mag(double f0_ph_s_m2, double flux_ph_s_m2)
{
	return -2.5 * log10(flux_ph_s_m2 / f0_ph_s_m2);
}

stray_real stray_moon_mag_at_phase(stray_real m_full, stray_real phase_deg)
{
	stray_real p = stray_fabs(phase_deg);

	return m_full + STRAY_R(0.026) * p + STRAY_R(4e-9) * p * p * p * p;
}

int stray_earth_flux(double f_sun_ph_s_m2, double albedo, double altitude_m,
		     double *flux_ph_s_m2, struct stray_error *err)
{
	double sin_rho;

	if (!(isfinite(albedo) && albedo >= 0.0 && albedo <= 1.0))
		return stray_error_set_value(err, STRAY_EINVAL, "albedo",
			STRAY_MSG("must lie in [0, 1]"), albedo);
	if (!(isfinite(altitude_m) && altitude_m > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "altitude",
			STRAY_MSG("must be finite and > 0"), altitude_m);
	sin_rho = STRAY_EARTH_RADIUS_M / (STRAY_EARTH_RADIUS_M + altitude_m);
	*flux_ph_s_m2 = albedo * f_sun_ph_s_m2 * sin_rho * sin_rho;
	return STRAY_OK;
}
