/*
 * spectral.c - wavelength-dependent coatings by re-weighting the recorded
 * paths (spectral.h).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/photometry.h"
#include "stray/spectrum_io.h"
#include "tracer/paths.h"
#include "tracer/spectral.h"

#define BAND_LO_NM 300.0
#define BAND_STEP_NM 10.0

int tracer_band_load(const char *source, const char *response,
		     struct tracer_band *b, struct stray_error *err)
{
	struct stray_spectrum_data s, r;
	double sum = 0.0;
	size_t i;
	int rc;

	memset(&s, 0, sizeof(s));
	memset(&r, 0, sizeof(r));
	memset(b, 0, sizeof(*b));
	rc = stray_spectrum_load(source ? source : TRACER_BAND_SOURCE, &s,
				 err);
	if (!rc)
		rc = stray_spectrum_load(response ? response :
					 TRACER_BAND_RESPONSE, &r, err);
	for (i = 0; !rc && i < TRACER_BAND_MAX; i++) {
		double l = BAND_LO_NM + BAND_STEP_NM * (double)i;
		double w = stray_spectrum_at(&s.s, l) *
			   stray_spectrum_at(&r.s, l) * l;	/* eq. 2.1 */

		if (w <= 0.0)
			continue;
		b->nm[b->n] = l;
		b->w[b->n++] = w;
		sum += w;
	}
	if (!rc && !(sum > 0.0))
		rc = stray_error_set(err, STRAY_EINVAL,
				     response ? response : "spectrum",
				     "source x response is zero over "
				     "300-1570 nm");
	for (i = 0; !rc && i < b->n; i++)
		b->w[i] /= sum;
	stray_spectrum_data_free(&s);
	stray_spectrum_data_free(&r);
	return rc;
}

int tracer_scene_spectral(const struct tracer_scene *s)
{
	size_t g;

	for (g = 0; g < s->mesh.n_group && g < TRACER_GROUP_MAX; g++)
		if (s->spectral[g].n > 0)
			return 1;
	return 0;
}

double tracer_rho_table_at(const struct tracer_rho_table *t, double nm)
{
	int k;

	if (nm <= t->nm[0])
		return t->rho[0];
	for (k = 1; k < t->n; k++)
		if (nm <= t->nm[k])
			return t->rho[k - 1] + (t->rho[k] - t->rho[k - 1]) *
				(nm - t->nm[k - 1]) / (t->nm[k] - t->nm[k - 1]);
	return t->rho[t->n - 1];
}

int tracer_result_apply_band(struct tracer_result *r,
			     const struct tracer_scene *s,
			     const struct tracer_band *b,
			     struct stray_error *err)
{
	double *grey, *spec;
	size_t i, j, e, n = r->n_theta * TRACER_ORDERS;
	int bt, o;

	grey = calloc(2 * (n ? n : 1), sizeof(*grey));
	if (!grey)
		return stray_error_set(err, STRAY_ENOMEM, "spectral",
				       "out of memory");
	spec = grey + n;
	for (e = 0; e < r->paths.cap; e++) {
		const struct tracer_path_entry *pe = &r->paths.e[e];
		int g[TRACER_SEQ_MAX], k, m;
		double gw = 1.0, sw = 0.0;

		if (!pe->used || pe->theta_index >= r->n_theta)
			continue;
		m = tracer_seq_unpack(pe->seq, g);
		for (k = 0; k < m; k++)
			gw *= s->material[g[k]].rho;
		for (i = 0; i < b->n; i++) {
			double x = b->w[i];

			for (k = 0; k < m; k++)
				x *= s->spectral[g[k]].n > 0 ?
				     tracer_rho_table_at(&s->spectral[g[k]],
							 b->nm[i]) :
				     s->material[g[k]].rho;
			sw += x;
		}
		o = m < TRACER_ORDERS - 1 ? m : TRACER_ORDERS - 1;
		if (o < 1)
			continue;
		grey[pe->theta_index * TRACER_ORDERS + o] += pe->value * gw;
		spec[pe->theta_index * TRACER_ORDERS + o] += pe->value * sw;
	}
	for (j = 0; j < r->n_theta; j++)
		for (o = 1; o < TRACER_ORDERS; o++) {
			double f = grey[j * TRACER_ORDERS + o] > 0.0 ?
				spec[j * TRACER_ORDERS + o] /
				grey[j * TRACER_ORDERS + o] : 1.0;

			for (bt = 0; bt < r->n_batches; bt++)
				r->power[((size_t)bt * r->n_theta + j) *
					 TRACER_ORDERS + o] *= f;
		}
	free(grey);
	return STRAY_OK;
}
