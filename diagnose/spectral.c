/*
 * spectral.c - the band a wavelength-dependent coating is weighted over
 * (diag_spectral.h) and the re-weighting of a cached trace by it.
 * Lambertian scatter does not depend on wavelength in geometry, so a
 * path's only spectral factor is prod rho(l) over its interior
 * vertices: the path table (tracer/paths.h) with its count of interior
 * scatters k re-weights exactly by M_k, with no re-trace.
 */
#include <math.h>
#include <string.h>

#include "diagnose/diag_spectral.h"
#include "stray/photometry.h"
#include "stray/spectrum_io.h"
#include "trace_cache.h"
#include "tracer/paths.h"

#define BAND_LO_NM 300.0
#define BAND_STEP_NM 10.0

static struct diag_band current;
static int have_current;

int diag_band_load(const char *source, const char *response,
		   struct diag_band *b, struct stray_error *err)
{
	struct stray_spectrum_data s, r;
	double sum = 0.0, sl = 0.0;
	size_t i;
	int rc;

	memset(&s, 0, sizeof(s));
	memset(&r, 0, sizeof(r));
	rc = stray_spectrum_load(source, &s, err);
	if (!rc)
		rc = stray_spectrum_load(response, &r, err);
	memset(b, 0, sizeof(*b));
	for (i = 0; !rc && i < DIAG_SPECTRAL_BINS; i++) {
		double l = BAND_LO_NM + BAND_STEP_NM * (double)i;
		/* photons: irradiance x l / (h c), eq. 2.1; constants cancel */
		double w = stray_spectrum_at(&s.s, l) *
			   stray_spectrum_at(&r.s, l) * l;

		if (w <= 0.0)
			continue;
		b->lambda_nm[b->n] = l;
		b->w[b->n++] = w;
		sum += w;
		sl += w * l;
	}
	if (!rc && !(sum > 0.0))
		rc = stray_error_set(err, STRAY_EINVAL, response,
				     "source x response is zero over "
				     "300-1570 nm");
	for (i = 0; !rc && i < b->n; i++)
		b->w[i] /= sum;
	if (!rc)
		b->lambda0_nm = sl / sum;
	stray_spectrum_data_free(&s);
	stray_spectrum_data_free(&r);
	return rc;
}

int diag_band_set(const char *source, const char *response,
		  struct stray_error *err)
{
	int rc = diag_band_load(source ? source : DIAG_SPECTRAL_DEFAULT_SOURCE,
				response ? response :
				DIAG_SPECTRAL_DEFAULT_RESPONSE, &current, err);

	have_current = rc == STRAY_OK;
	return rc;
}

const struct diag_band *diag_band_current(void)
{
	struct stray_error err;

	stray_error_clear(&err);
	if (!have_current)
		diag_band_set(NULL, NULL, &err);	/* built-ins: cannot fail */
	return have_current ? &current : NULL;
}

void diag_band_moments(const struct diag_band *b, double rho, double slope,
		       double *pw, int kmax)
{
	size_t i;
	int k;

	for (k = 0; k <= kmax; k++)
		pw[k] = 0.0;
	for (i = 0; i < b->n; i++) {
		double r = rho * pow(b->lambda_nm[i] / b->lambda0_nm, slope),
		       x = b->w[i];

		for (k = 0; k <= kmax; k++, x *= r)
			pw[k] += x;
	}
}

/* As diag_trace_power with a spectral coating: row of k interior
 * scatters x M_k (its variance x M_k^2). */
void diag_trace_power_band(const struct diag_trace *t, double rho,
			   double slope, double *p, double *var)
{
	double pw[TRACER_SEQ_MAX + 1];
	size_t i;

	if (isnan(rho))
		rho = t->base_rho;
	diag_band_moments(diag_band_current(), rho, slope, pw,
			  TRACER_SEQ_MAX);
	memset(p, 0, t->n_theta * sizeof(*p));
	memset(var, 0, t->n_theta * sizeof(*var));
	for (i = 0; i < t->n_e; i++) {
		double f = pw[t->n_int[i]];

		p[t->j[i]] += t->v[i] * f;
		var[t->j[i]] += t->var[i] * f * f;
	}
}
