/*
 * colour.c - the colour term of catalogue magnitudes (stray/colour.h).
 */
#include <math.h>

#include "stray/colour.h"
#include "stray/spectrum_io.h"

#define GRID_N 161		/* 300 .. 1100 nm, 5 nm: covers QE and V */
#define HC_K 1.438776877e7	/* h c / k [nm K] */

double stray_bv_temperature(double b_v)
{
	double b = fmax(STRAY_COLOUR_BV_MIN, fmin(STRAY_COLOUR_BV_MAX, b_v));

	return 4600.0 * (1.0 / (0.92 * b + 1.7) + 1.0 / (0.92 * b + 0.62));
}

/* photon flux through qe over energy flux through v of a blackbody at t
 * (any common scale: the ratio is used) */
static int ratio(double t, const struct stray_spectrum *qe,
		 const struct stray_spectrum *v, double *out,
		 struct stray_error *err)
{
	double wl[GRID_N], bb[GRID_N], bbe[GRID_N], fq, fv;
	struct stray_spectrum s = { GRID_N, wl, bb }, se = { GRID_N, wl, bbe };
	int i, rc;

	for (i = 0; i < GRID_N; i++) {
		double l = 300.0 + 5.0 * i;

		wl[i] = l;
		/* Planck's B_lambda up to a constant (l in nm) */
		bb[i] = 1e15 / (pow(l, 5.0) * expm1(HC_K / (l * t)));
		/* eq. 2.1 counts photons (f l / hc); V weighs energy: f / l
		 * through the same integral gives the energy integral */
		bbe[i] = bb[i] / l;
	}
	if ((rc = stray_photon_flux(&s, qe, &fq, err)) != STRAY_OK ||
	    (rc = stray_photon_flux(&se, v, &fv, err)) != STRAY_OK)
		return rc;
	if (!(fv > 0.0) || !(fq > 0.0))
		return stray_error_set(err, STRAY_EINVAL, "qe",
				       "no flux of a blackbody in the passband");
	*out = fq / fv;
	return STRAY_OK;
}

int stray_colour_init(struct stray_colour *c, const struct stray_spectrum *qe,
		      const struct stray_spectrum *v_band,
		      struct stray_error *err)
{
	double r0;
	int k, rc;

	if ((rc = ratio(stray_bv_temperature(0.0), qe, v_band, &r0, err)))
		return rc;
	for (k = 0; k < STRAY_COLOUR_N; k++) {
		double r;

		if ((rc = ratio(stray_bv_temperature(STRAY_COLOUR_BV_MIN +
						     0.02 * k), qe, v_band,
				&r, err)) != STRAY_OK)
			return rc;
		c->f[k] = r / r0;
	}
	return STRAY_OK;
}

int stray_colour_for_qe(struct stray_colour *c, const char *qe,
			struct stray_error *err)
{
	struct stray_spectrum_data q, v;
	int rc = stray_spectrum_load(qe, &q, err);

	if (rc != STRAY_OK)
		return rc;
	rc = stray_spectrum_load("builtin:bessell_v_passband", &v, err);
	if (rc == STRAY_OK) {
		rc = stray_colour_init(c, &q.s, &v.s, err);
		stray_spectrum_data_free(&v);
	}
	stray_spectrum_data_free(&q);
	return rc;
}

double stray_colour_factor(const struct stray_colour *c, double b_v)
{
	double x = (fmax(STRAY_COLOUR_BV_MIN, fmin(STRAY_COLOUR_BV_MAX, b_v)) -
		    STRAY_COLOUR_BV_MIN) / 0.02;
	int k = (int)floor(x);

	if (!isfinite(x) || k < 0)
		return c->f[0];
	if (k >= STRAY_COLOUR_N - 1)
		return c->f[STRAY_COLOUR_N - 1];
	return c->f[k] + (x - k) * (c->f[k + 1] - c->f[k]);
}

void stray_colour_apply(const struct stray_colour *c,
			struct stray_cat_star *s, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++)
		s[i].colour = stray_colour_factor(c, s[i].b_v);
}
