/*
 * common.c - frame-common noise (reduce_common.h): the scatter of whole-
 * frame totals over a group's repeats beyond the pixels' own variances,
 * pooled over the sweep by inverse-variance weights.
 */
#include <string.h>

#include "stray/reduce_common.h"

void stray_common_group_reset(struct stray_common_group *g)
{
	memset(g, 0, sizeof(*g));
}

int stray_common_group_add(struct stray_common_group *g,
			   const struct stray_dark_model *d,
			   const struct stray_frame *f, const uint8_t *mask,
			   double x, struct stray_error *err)
{
	const struct stray_dark_level *l;
	double s = 0.0, inv;
	size_t r, c, li;
	int rc;

	if ((rc = stray_dark_find(d, f->t_exp_s, &li, err)) != STRAY_OK)
		return rc;
	l = &d->lvl[li];
	inv = 1.0 / (f->t_exp_s * f->nd_trans * f->monitor);
	for (r = 0; r < f->n_rows; r++) {
		const uint16_t *row = f->pix + r * f->n_cols;
		const uint8_t *m = mask ? mask + r * f->n_cols : NULL;
		double lvl[4];
		unsigned k;

		for (k = 0; k < 4; k++)
			lvl[k] = l->mean[stray_bayer_channel(&d->map,
					f->det_row[r], f->col0 + (long)k)];
		for (c = 0; c < f->n_cols; c++) {
			if (m && m[c] != STRAY_PIX_OK)
				continue;
			if (row[c] >= f->sat_level)
				g->incomplete = 1;
			/* eq. 3.4-3.5, per unit t alpha_nd as in accum.c */
			s += (row[c] - lvl[c & 3]) * inv;
		}
	}
	if (g->n == 0) {
		g->s0 = s;
		g->x0 = x;
	}
	s -= g->s0;
	x -= g->x0;
	g->n++;
	g->ss += s;
	g->sss += s * s;
	g->sx += x;
	g->sxx += x * x;
	g->sxs += x * s;
	return STRAY_OK;
}

void stray_common_group_finish(struct stray_common_group *g,
			       const struct stray_accum *a,
			       const uint8_t *mask)
{
	size_t i;

	g->v_ind = 0.0;
	for (i = 0; i < a->n_pix; i++)
		if ((!mask || mask[i] == STRAY_PIX_OK) && a->n[i] >= 2)
			g->v_ind += a->m2[i] / (a->n[i] - 1.0);
}

double stray_common_group_mean(const struct stray_common_group *g)
{
	return g->n ? g->s0 + g->ss / (double)g->n : 0.0;
}

size_t stray_common_group_stats(const struct stray_common_group *g,
				double beta, double *est, double *ind)
{
	double n = (double)g->n, mean = stray_common_group_mean(g);
	double vss, vxs, vxx, b, var_r, s2;

	*est = *ind = 0.0;
	if (g->n < 2 || g->incomplete || !(mean != 0.0))
		return 0;
	/* centred sums of squares and products */
	vss = g->sss - g->ss * g->ss / n;
	vxs = g->sxs - g->sx * g->ss / n;
	vxx = g->sxx - g->sx * g->sx / n;
	/* residuals S_k - Sbar beta (x_k - xbar): the drift taken out */
	b = mean * beta;
	var_r = (vss - 2.0 * b * vxs + b * b * vxx) / (n - 1.0);
	s2 = mean * mean;
	*est = (var_r - g->v_ind) / s2;
	*ind = g->v_ind / s2;
	return g->n - 1;
}

double stray_common_fit(const double *est, const double *ind,
			const size_t *dof, size_t n)
{
	double s2 = 0.0;
	int it;
	size_t i;

	for (it = 0; it < 30; it++) {
		double sw = 0.0, swe = 0.0;

		for (i = 0; i < n; i++) {
			double w, d = s2 + ind[i];

			if (dof[i] == 0 || !(d > 0.0))
				continue;
			w = (double)dof[i] / (d * d);
			sw += w;
			swe += w * est[i];
		}
		s2 = sw > 0.0 && swe > 0.0 ? swe / sw : 0.0;
	}
	return s2;
}
