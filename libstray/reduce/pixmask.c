/*
 * pixmask.c - hot and dead pixels from the dark frames (thesis §3.2): the
 * per-pixel dark excess over its channel level, classified against the
 * robust spread of all pixels.
 */
#include <math.h>

#include "stray/reduce_dark.h"

void stray_pixstat_init(struct stray_pixstat *s, size_t n_pix, double *mean,
			double *m2)
{
	size_t i;

	s->n_pix = n_pix;
	s->mean = mean;
	s->m2 = m2;
	s->n = 0;
	for (i = 0; i < n_pix; i++)
		mean[i] = m2[i] = 0.0;
}

int stray_pixstat_add(struct stray_pixstat *s,
		      const struct stray_dark_model *m,
		      const struct stray_frame *f, struct stray_error *err)
{
	const struct stray_dark_level *l;
	double k;
	size_t r, c, li;
	int rc;

	if (f->n_rows * f->n_cols != s->n_pix)
		return stray_error_set_value(err, STRAY_EINVAL, "NAXIS",
			"frame size differs from the first frame",
			(double)(f->n_rows * f->n_cols));
	if ((rc = stray_dark_find(m, f->t_exp_s, &li, err)) != STRAY_OK)
		return rc;
	l = &m->lvl[li];
	s->n++;
	k = 1.0 / (double)s->n;
	for (r = 0; r < f->n_rows; r++) {
		const uint16_t *row = f->pix + r * f->n_cols;
		size_t base = r * f->n_cols;
		double lvl[4];
		unsigned ph;

		for (ph = 0; ph < 4; ph++)	/* the channel repeats every 4 */
			lvl[ph] = l->mean[stray_bayer_channel(&m->map,
				f->det_row[r], f->col0 + (long)ph)];
		for (c = 0; c < f->n_cols; c++) {
			double x = row[c] - lvl[c & 3];
			double d = x - s->mean[base + c];

			/* Welford (1962): running mean and sum of squares. */
			s->mean[base + c] += d * k;
			s->m2[base + c] += d * (x - s->mean[base + c]);
		}
	}
	return STRAY_OK;
}

/* k-th smallest of v[0..n) by Hoare's selection (reorders v). */
static double select_kth(double *v, size_t n, size_t k)
{
	size_t lo = 0, hi = n - 1;

	while (lo < hi) {	/* each pass shrinks [lo, hi] */
		double pivot = v[lo + (hi - lo) / 2];
		size_t i = lo, j = hi;

		while (i <= j) {
			while (v[i] < pivot)
				i++;
			while (v[j] > pivot)
				j--;
			if (i <= j) {
				double t = v[i];

				v[i] = v[j];
				v[j] = t;
				i++;
				if (j == 0)
					break;
				j--;
			}
		}
		if (k <= j)
			hi = j;
		else if (k >= i)
			lo = i;
		else
			break;
	}
	return v[k];
}

/* Median of v[0..n) (n >= 1), reordering v. */
static double median_sorting(double *v, size_t n)
{
	double hi = select_kth(v, n, n / 2), lo = hi;
	size_t i;

	if (n % 2 == 0) {	/* the largest of the lower half */
		lo = v[0];
		for (i = 1; i < n / 2; i++)
			lo = v[i] > lo ? v[i] : lo;
	}
	return 0.5 * (lo + hi);
}

int stray_mask_build(const struct stray_pixstat *s, double hot_sigma,
		     uint8_t *mask, double *scratch,
		     struct stray_mask_stats *out, struct stray_error *err)
{
	double med, spread;
	size_t i;

	if (s->n < 2)
		return stray_error_set_value(err, STRAY_EINVAL, "FRAMETYP",
			"need at least 2 DARK frames to find hot pixels",
			(double)s->n);
	if (!(isfinite(hot_sigma) && hot_sigma > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "hot_sigma",
			"must be finite and > 0", hot_sigma);
	for (i = 0; i < s->n_pix; i++)
		scratch[i] = s->mean[i];
	med = median_sorting(scratch, s->n_pix);
	for (i = 0; i < s->n_pix; i++)
		scratch[i] = fabs(s->mean[i] - med);
	/* 1.4826 MAD estimates a Gaussian sigma; floor it for quiet data. */
	spread = fmax(1.4826 * median_sorting(scratch, s->n_pix), 0.25);
	out->n_hot = out->n_dead = 0;
	out->excess_median = med;
	out->excess_sigma = spread;
	for (i = 0; i < s->n_pix; i++) {
		double e = s->mean[i] - med;

		mask[i] = STRAY_PIX_OK;
		if (e > hot_sigma * spread) {
			mask[i] = STRAY_PIX_HOT;
			out->n_hot++;
		} else if (e < -hot_sigma * spread ||
			   (s->n >= 4 && s->m2[i] == 0.0)) {
			mask[i] = STRAY_PIX_DEAD;
			out->n_dead++;
		}
	}
	return STRAY_OK;
}
