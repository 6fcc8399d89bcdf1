/*
 * common.c - frame-common noise (reduce_common.h): the scatter of whole-
 * frame totals over a group's repeats beyond the pixels' own variances,
 * pooled over the sweep by inverse-variance weights.
 */
#include <string.h>

#include "stray/reduce_common.h"
#include "pixel_sums.h"

void stray_common_group_reset(struct stray_common_group *g)
{
	memset(g, 0, sizeof(*g));
}

/*
 * The sum of (I - D) over the unmasked pixels of a piece of a row (at
 * most STRAY_PIECE_MAX columns, from a multiple of 4), per column phase
 * c & 3 (one dark level each): the samples summed exactly in integers,
 * the levels taken off once per phase.  *sat is set when an unmasked
 * sample is saturated.
 */
STRAY_VECTOR_CLONES
static double row_total(const uint16_t *restrict row,
			const uint8_t *restrict m, size_t n_cols,
			const double *lvl, int sat_at, int *sat)
{
	/* at most 1024 samples of < 2^16 a phase: exact in 32 bits */
	uint32_t s0 = 0, s1 = 0, s2 = 0, s3 = 0;
	uint32_t n0 = 0, n1 = 0, n2 = 0, n3 = 0;
	unsigned hit = 0;
	size_t c;

	for (c = 0; c + 4 <= n_cols; c += 4) {
		unsigned k0 = m[c] == STRAY_PIX_OK, k1 = m[c + 1] == STRAY_PIX_OK;
		unsigned k2 = m[c + 2] == STRAY_PIX_OK;
		unsigned k3 = m[c + 3] == STRAY_PIX_OK;

		s0 += k0 ? row[c] : 0u;
		s1 += k1 ? row[c + 1] : 0u;
		s2 += k2 ? row[c + 2] : 0u;
		s3 += k3 ? row[c + 3] : 0u;
		n0 += k0, n1 += k1, n2 += k2, n3 += k3;
		hit |= (k0 & (row[c] >= sat_at)) |
		       (k1 & (row[c + 1] >= sat_at)) |
		       (k2 & (row[c + 2] >= sat_at)) |
		       (k3 & (row[c + 3] >= sat_at));
	}
	for (; c < n_cols; c++) {
		unsigned k = m[c] == STRAY_PIX_OK;
		uint32_t v = k ? row[c] : 0u;

		switch (c & 3) {
		case 0: s0 += v, n0 += k; break;
		case 1: s1 += v, n1 += k; break;
		case 2: s2 += v, n2 += k; break;
		default: s3 += v, n3 += k; break;
		}
		hit |= k & (row[c] >= sat_at);
	}
	*sat |= hit != 0;
	return ((double)s0 - (double)n0 * lvl[0]) +
	       ((double)s1 - (double)n1 * lvl[1]) +
	       ((double)s2 - (double)n2 * lvl[2]) +
	       ((double)s3 - (double)n3 * lvl[3]);
}

int stray_common_group_add(struct stray_common_group *g,
			   const struct stray_dark_model *d,
			   const struct stray_frame *f, const uint8_t *mask,
			   double x, struct stray_error *err)
{
	const struct stray_dark_level *l;
	double s = 0.0, inv;
	size_t r, li;
	int rc, sat_at;

	if ((rc = stray_dark_find(d, f->t_exp_s, &li, err)) != STRAY_OK)
		return rc;
	l = &d->lvl[li];
	inv = 1.0 / (f->t_exp_s * f->nd_trans * f->monitor);
	sat_at = stray_frame_sat_at(f);
	for (r = 0; r < f->n_rows; r++) {
		double lvl[4], row = 0.0;
		size_t c, len;
		unsigned k;

		for (k = 0; k < 4; k++)
			lvl[k] = l->mean[stray_bayer_channel(&d->map,
					f->det_row[r], f->col0 + (long)k)];
		/* eq. 3.4-3.5, per unit t alpha_nd as in accum.c */
		for (c = 0; c < f->n_cols; c += len) {
			const uint8_t *m;

			len = f->n_cols - c;
			m = stray_mask_piece(mask ? mask + r * f->n_cols : NULL,
					     c, &len);
			row += row_total(f->pix + r * f->n_cols + c, m, len,
					 lvl, sat_at, &g->incomplete);
		}
		s += row * inv;
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
			       const struct stray_accum_var *v)
{
	g->v_ind = v->kept_var;
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
