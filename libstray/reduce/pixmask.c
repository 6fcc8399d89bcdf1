/*
 * pixmask.c - hot and dead pixels from the dark frames (thesis §3.2): the
 * per-pixel dark excess over its channel level, classified against the
 * robust spread of all pixels.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

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

/* Welford (1962): running mean and sum of squares of x = row - level. */
static inline void welford_px(double *restrict mean, double *restrict m2,
			      const uint16_t *restrict row, size_t c,
			      double lc, double k)
{
	double x = row[c] - lc;
	double d = x - mean[c];

	mean[c] += d * k;
	m2[c] += d * (x - mean[c]);
}

/* One row, four columns (one Bayer period) a step so the loop
 * vectorises: the same arithmetic pixel by pixel. */
static void welford_row(double *restrict mean, double *restrict m2,
			const uint16_t *restrict row, size_t n_cols,
			const double *lvl, double k)
{
	double l0 = lvl[0], l1 = lvl[1], l2 = lvl[2], l3 = lvl[3];
	size_t c;

	for (c = 0; c + 4 <= n_cols; c += 4) {
		welford_px(mean, m2, row, c, l0, k);
		welford_px(mean, m2, row, c + 1, l1, k);
		welford_px(mean, m2, row, c + 2, l2, k);
		welford_px(mean, m2, row, c + 3, l3, k);
	}
	for (; c < n_cols; c++)
		welford_px(mean, m2, row, c, lvl[c & 3], k);
}

int stray_pixstat_add(struct stray_pixstat *s,
		      const struct stray_dark_model *m,
		      const struct stray_frame *f, struct stray_error *err)
{
	const struct stray_dark_level *l;
	double k;
	size_t r, li;
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
		welford_row(s->mean + base, s->m2 + base, row, f->n_cols, lvl,
			    k);
	}
	return STRAY_OK;
}

/*
 * The median by radix selection (exact, O(n), no comparisons to
 * mispredict): doubles as order-preserving 64-bit keys, the candidates
 * narrowed 12 bits a step by a histogram of that digit (the last step
 * overlaps bits already shared: harmless).
 */
#define DIGIT_BITS 12
#define DIGIT_BINS (1u << DIGIT_BITS)

/* Order-preserving key of a finite double (+0.0 and -0.0 alike). */
static uint64_t key_of(double x)
{
	uint64_t u;

	x += 0.0;		/* -0.0 -> +0.0 */
	memcpy(&u, &x, sizeof(u));
	return u >> 63 ? ~u : u | 0x8000000000000000ull;
}

static double value_of(uint64_t k)
{
	uint64_t u = k >> 63 ? k & 0x7fffffffffffffffull : ~k;
	double x;

	memcpy(&x, &u, sizeof(x));
	return x;
}

/* Bucket holding rank k of a histogram; *below: the count under it. */
static unsigned bucket_of(const uint32_t *h, size_t k, size_t *below)
{
	size_t cum = 0;
	unsigned b;

	for (b = 0; b + 1 < DIGIT_BINS && cum + h[b] <= k; b++)
		cum += h[b];
	*below = cum;
	return b;
}

/*
 * Ranks k - 1 and k (1 <= k < n) of key[0..n) into *lo and *hi
 * (reorders key; hist DIGIT_BINS counters).  While both ranks share a
 * bucket the candidates shrink to it; once they part, the lower is the
 * largest of its bucket and the upper the smallest of its own.
 */
static void select_pair(uint64_t *key, size_t n, size_t k, uint32_t *hist,
			uint64_t *lo, uint64_t *hi)
{
	int shift = 64 - DIGIT_BITS;

	for (;;) {
		size_t i, m = 0, below_lo, below_hi;
		unsigned b_lo, b_hi;
		uint64_t mx = 0, mn = ~0ull;

		memset(hist, 0, DIGIT_BINS * sizeof(*hist));
		for (i = 0; i < n; i++)
			hist[(key[i] >> shift) & (DIGIT_BINS - 1)]++;
		b_lo = bucket_of(hist, k - 1, &below_lo);
		b_hi = bucket_of(hist, k, &below_hi);
		if (b_lo != b_hi) {
			for (i = 0; i < n; i++) {
				unsigned b = (key[i] >> shift) &
					     (DIGIT_BINS - 1);

				if (b == b_lo && key[i] > mx)
					mx = key[i];
				if (b == b_hi && key[i] < mn)
					mn = key[i];
			}
			*lo = mx;
			*hi = mn;
			return;
		}
		for (i = 0; i < n; i++) {	/* keep the shared bucket */
			key[m] = key[i];	/* (no branch to mispredict) */
			m += ((key[i] >> shift) & (DIGIT_BINS - 1)) == b_lo;
		}
		n = m;
		k -= below_lo;
		if (shift == 0)
			break;
		shift = shift > DIGIT_BITS ? shift - DIGIT_BITS : 0;
	}
	*lo = *hi = key[0];	/* all 64 bits agree */
}

/* Median of the n keys (n >= 1): the middle one, or the mean of the
 * middle two (reorders key). */
static double median_keys(uint64_t *key, size_t n, uint32_t *hist)
{
	uint64_t lo, hi;

	if (n == 1)
		return value_of(key[0]);
	select_pair(key, n, n / 2, hist, &lo, &hi);
	if (n % 2)
		lo = hi;
	return 0.5 * (value_of(lo) + value_of(hi));
}

int stray_mask_build(const struct stray_pixstat *s, double hot_sigma,
		     uint8_t *mask, double *scratch,
		     struct stray_mask_stats *out, struct stray_error *err)
{
	uint64_t *key = (uint64_t *)scratch;	/* same 8 bytes a pixel */
	uint32_t hist[DIGIT_BINS];
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
		key[i] = key_of(s->mean[i]);
	med = median_keys(key, s->n_pix, hist);
	for (i = 0; i < s->n_pix; i++)
		key[i] = key_of(fabs(s->mean[i] - med));
	/* 1.4826 MAD estimates a Gaussian sigma; floor it for quiet data. */
	spread = fmax(1.4826 * median_keys(key, s->n_pix, hist), 0.25);
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
