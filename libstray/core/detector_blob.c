/*
 * detector_blob.c - THRESHOLD's lost-star model (stray/detector.h): the
 * star is found when the 8-connected component of above-threshold pixels
 * through one of its four nearest pixels holds >= min_px pixels.
 *
 * With pixels independent (pixel i above with probability q_i), the
 * component C(s) through a seed s is exactly the animal A when every
 * cell of A is above and every cell of its perimeter dA below, so
 *
 *   Pr(|C(s)| >= m) = q_s - sum_{A containing s, |A| < m}
 *                           prod_{i in A} q_i prod_{j in dA} (1 - q_j)   (1)
 *
 * (the cluster-size distribution of site percolation, Stauffer & Aharony
 * 1994, "Introduction to Percolation Theory", eq. 2.1, here with a q that
 * varies over the star's pixels).  The four seeds (the 2 x 2 pixels about
 * the star) touch each other, so when a seed is above, every other seed
 * above lies in its component: the star is missed by the seeds one after
 * another only through seeds that are below, and
 *
 *   Pr(found) = sum_k prod_{j<k} (1 - q_sj) Pr(|C(s_k)| >= m | s_j<k below)  (2)
 *
 * where the condition drops the animals holding an earlier seed and sets
 * an earlier seed on the perimeter to "below" with probability 1.  (2) is
 * exact for components through the seeds; one that misses all four (a
 * ring about a faint star) is left out.  The earlier rule (>= m of the
 * pixels within 2.5 px above, taken as connected) counted scattered
 * pixels as a star: 0.06-0.09 too high on rendered frames at 2-2.5e-7
 * once the ADC's steps are modelled (tests/frames/test_detect_gap.c).
 * Freestanding: no heap, no recursion, every loop bounded.
 */
#include "stray/detector_blob.h"
#include "stray/detector_pixel.h"
#include "stray/tail.h"

#define HALF 3			/* animal cells within +-3 of the seed */
#define SIDE (2 * HALF + 1)
#define GRID 11			/* q on the star's pixels -5..5 */
#define GHALF 5

typedef unsigned long long mask_t;	/* SIDE * SIDE = 49 bits */

static mask_t bit(int dx, int dy)
{
	return (mask_t)1 << ((dy + HALF) * SIDE + dx + HALF);
}

static unsigned char code(int dx, int dy)
{
	return (unsigned char)((dy + 4) * 9 + dx + 4);
}

/* One animal's cells and 8-neighbour perimeter as codes. */
static int fill_animal(mask_t a, struct stray_det_animal *out)
{
	unsigned char seen[81];
	int x, y, u, v;
	unsigned i;

	for (i = 0; i < 81; i++)
		seen[i] = 0;
	out->n_cell = out->n_per = 0;
	for (y = -HALF; y <= HALF; y++)
		for (x = -HALF; x <= HALF; x++)
			if (a & bit(x, y)) {
				if (out->n_cell >= STRAY_DET_BLOB_PX_MAX - 1)
					return -1;
				out->cell[out->n_cell++] = code(x, y);
				seen[code(x, y)] = 1;
			}
	for (y = -HALF; y <= HALF; y++)
		for (x = -HALF; x <= HALF; x++) {
			if (!(a & bit(x, y)))
				continue;
			for (v = y - 1; v <= y + 1; v++)
				for (u = x - 1; u <= x + 1; u++) {
					if (seen[code(u, v)])
						continue;
					if (out->n_per >= STRAY_DET_PERIM_MAX)
						return -1;
					seen[code(u, v)] = 1;
					out->per[out->n_per++] = code(u, v);
				}
		}
	return 0;
}

int stray_detector_blob_setup(struct stray_detector *d,
			      struct stray_error *err)
{
	mask_t m[STRAY_DET_ANIMALS_MAX];
	unsigned n = 1, lo = 0, hi = 1, s, i, j, k;
	int x, y, u, v;

	d->n_animal = 0;
	if (d->kind != STRAY_DET_THRESHOLD || d->min_px > STRAY_DET_BLOB_PX_MAX)
		return STRAY_OK;
	m[0] = bit(0, 0);
	/* level s from level s - 1: add any 8-neighbour, keep new shapes */
	for (s = 2; s < d->min_px; s++) {
		for (i = lo; i < hi; i++)
			for (y = -HALF; y <= HALF; y++)
				for (x = -HALF; x <= HALF; x++) {
					if (!(m[i] & bit(x, y)))
						continue;
					for (v = y - 1; v <= y + 1; v++)
						for (u = x - 1; u <= x + 1; u++) {
							mask_t a;

							if (u < -HALF || u > HALF ||
							    v < -HALF || v > HALF ||
							    (m[i] & bit(u, v)))
								continue;
							a = m[i] | bit(u, v);
							for (j = hi; j < n && m[j] != a; j++)
								;
							if (j < n)
								continue;
							if (n >= STRAY_DET_ANIMALS_MAX)
								return stray_error_set(err,
									STRAY_ERANGE, "detector_min_px",
									STRAY_MSG("animal table full"));
							m[n++] = a;
						}
				}
		lo = hi;
		hi = n;
	}
	for (k = 0; k < n; k++)
		if (fill_animal(m[k], &d->animal[k]) != 0)
			return stray_error_set(err, STRAY_ERANGE,
				"detector_min_px", STRAY_MSG("animal perimeter too long"));
	d->n_animal = n;
	return STRAY_OK;
}

static stray_real gauss_cdf(stray_real z)
{
	return STRAY_R(0.5) * stray_erfc(-z * STRAY_R(0.70710678118654752440));
}

stray_real stray_detector_blob_prob(const struct stray_detector *d,
				    stray_real b, stray_real star,
				    stray_real ox, stray_real oy, stray_real t)
{
	static const int seed[4][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } };
	stray_real q[GRID * GRID], p = 0, below = 1;
	unsigned a, c, k, j;
	int i, jj;

	for (jj = -GHALF; jj <= GHALF; jj++)
		for (i = -GHALF; i <= GHALF; i++) {
			stray_real s = star * stray_detector_psf_pixel(
				d->psf_sigma_px, ox, oy, i, jj), v = s + b;

			q[(jj + GHALF) * GRID + i + GHALF] = v > 0 ?
				gauss_cdf((s - t) / stray_sqrt(v)) :
				(stray_real)(s > t);
		}
	for (k = 0; k < 4; k++) {
		int sx = seed[k][0], sy = seed[k][1];
		unsigned char early[3];
		stray_real sum = 0, qs = q[(sy + GHALF) * GRID + sx + GHALF];

		for (j = 0; j < k; j++)	/* earlier seeds, about this one */
			early[j] = code(seed[j][0] - sx, seed[j][1] - sy);
		for (a = 0; a < d->n_animal; a++) {
			const struct stray_det_animal *an = &d->animal[a];
			stray_real prod = 1;
			int skip = 0;

			for (c = 0; c < an->n_cell && !skip; c++)
				for (j = 0; j < k; j++)
					skip |= an->cell[c] == early[j];
			if (skip)
				continue;
			for (c = 0; c < an->n_cell; c++) {
				int cx = an->cell[c] % 9 - 4 + sx;
				int cy = an->cell[c] / 9 - 4 + sy;

				prod *= q[(cy + GHALF) * GRID + cx + GHALF];
			}
			for (c = 0; c < an->n_per && prod > 0; c++) {
				int px = an->per[c] % 9 - 4 + sx;
				int py = an->per[c] / 9 - 4 + sy;
				int known = 0;

				for (j = 0; j < k; j++)
					known |= an->per[c] == early[j];
				if (!known)
					prod *= 1 - q[(py + GHALF) * GRID + px + GHALF];
			}
			sum += prod;
		}
		if (qs - sum > 0)
			p += below * (qs - sum);
		below *= 1 - qs;
	}
	return p > 1 ? 1 : p;
}
