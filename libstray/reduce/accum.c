/*
 * accum.c - the temporal mean of the repeated frames of one group (thesis
 * §3.2: 3 consecutive frames averaged), as light rates
 * (I - D(t)) / (t_exp alpha_nd monitor) (eq. 3.4-3.6), saturated samples
 * left out and counted.
 */
#include <string.h>

#include "stray/reduce_response.h"
#include "pixel_sums.h"

const uint8_t stray_all_ok[STRAY_PIECE_MAX];

/* Layout in the caller's block: mean, m2 (float), then n (uint16). */
size_t stray_accum_bytes(size_t n_pix)
{
	return (10 * n_pix + 7) / 8 * 8;
}

void stray_accum_init(struct stray_accum *a, size_t n_pix, void *mem)
{
	unsigned char *p = mem;

	a->n_pix = n_pix;
	a->mean = (float *)p;
	a->m2 = (float *)(p + 4 * n_pix);
	a->n = (uint16_t *)(p + 8 * n_pix);
	stray_accum_reset(a);
}

void stray_accum_reset(struct stray_accum *a)
{
	memset(a->mean, 0, a->n_pix * sizeof(*a->mean));
	memset(a->m2, 0, a->n_pix * sizeof(*a->m2));
	memset(a->n, 0, a->n_pix * sizeof(*a->n));
	a->n_frames = 0;
	a->n_sat = 0;
	a->inv_scale_sum = 0.0;
	memset(a->dcoef, 0, sizeof(a->dcoef));
}

/*
 * Welford's update of one pixel with the rate x; inv_next is 1/(n + 1)
 * for the usual pixel, seen in every frame so far (no division then).
 */
static void welford(struct stray_accum *a, size_t i, double x,
		    double inv_next)
{
	double mean = a->mean[i];
	double d = x - mean;
	unsigned n = (unsigned)a->n[i] + 1u;

	mean += n == a->n_frames + 1u ? d * inv_next : d / n;
	a->m2[i] += (float)(d * (x - mean));
	a->mean[i] = (float)mean;
	a->n[i] = (uint16_t)n;
}

/* Whether a row is the usual one: no sample saturated, every pixel seen
 * in every frame so far (a reduction the compiler vectorises). */
static int usual_row(const uint16_t *restrict row, const uint16_t *restrict nn,
		     size_t n_cols, int sat_at, unsigned n_frames)
{
	int odd = 0;
	size_t c;

	for (c = 0; c < n_cols; c++)
		odd |= (row[c] >= sat_at) | (nn[c] != n_frames);
	return !odd;
}

/* welford() of pixel c of a usual row with x = (row[c] - lc) inv. */
static inline void welford_usual(float *restrict mean, float *restrict m2,
				 uint16_t *restrict nn,
				 const uint16_t *restrict row, size_t c,
				 double lc, double inv, double inv_next)
{
	double x = (row[c] - lc) * inv;
	double mu = mean[c], d = x - mu;

	mu += d * inv_next;
	m2[c] += (float)(d * (x - mu));
	mean[c] = (float)mu;
	nn[c] = (uint16_t)(nn[c] + 1u);
}

/*
 * welford() over a usual row, x = (row[c] - lvl[c & 3]) inv: the same
 * arithmetic pixel by pixel, without branches, four columns (one Bayer
 * period) a step, so the loop vectorises.
 */
STRAY_VECTOR_CLONES
static void welford_usual_row(float *restrict mean, float *restrict m2,
			      uint16_t *restrict nn,
			      const uint16_t *restrict row, size_t n_cols,
			      const double *lvl, double inv, double inv_next)
{
	double l0 = lvl[0], l1 = lvl[1], l2 = lvl[2], l3 = lvl[3];
	size_t c;

	for (c = 0; c + 4 <= n_cols; c += 4) {
		welford_usual(mean, m2, nn, row, c, l0, inv, inv_next);
		welford_usual(mean, m2, nn, row, c + 1, l1, inv, inv_next);
		welford_usual(mean, m2, nn, row, c + 2, l2, inv, inv_next);
		welford_usual(mean, m2, nn, row, c + 3, l3, inv, inv_next);
	}
	for (; c < n_cols; c++)
		welford_usual(mean, m2, nn, row, c, lvl[c & 3], inv, inv_next);
}

int stray_accum_add(struct stray_accum *a, const struct stray_dark_model *d,
		    const struct stray_frame *f, struct stray_error *err)
{
	double n_ch[STRAY_BAYER_CHANNELS] = { 0 };
	const struct stray_dark_level *l;
	double inv, inv_next;
	size_t r, c, li, i0;
	unsigned ch;
	int sat_at;
	int rc;

	if ((rc = stray_frame_check(f, err)) != STRAY_OK)
		return rc;
	if (f->n_rows * f->n_cols != a->n_pix)
		return stray_error_set_value(err, STRAY_EINVAL, "NAXIS",
			"frame size differs from the first frame",
			(double)(f->n_rows * f->n_cols));
	if (a->n_frames >= 65535u)
		return stray_error_set(err, STRAY_ERANGE, "SEQNUM",
				       "more than 65535 frames in one group");
	if ((rc = stray_dark_find(d, f->t_exp_s, &li, err)) != STRAY_OK)
		return rc;
	l = &d->lvl[li];
	inv = 1.0 / (f->t_exp_s * f->nd_trans * f->monitor);
	inv_next = 1.0 / ((double)a->n_frames + 1.0);
	sat_at = stray_frame_sat_at(f);
	for (r = 0; r < f->n_rows; r++) {
		const uint16_t *row = f->pix + r * f->n_cols;
		double lvl[4];
		unsigned ph[4], k;

		/* The channel repeats every 4 columns: look it up once. */
		for (k = 0; k < 4; k++) {
			ph[k] = stray_bayer_channel(&d->map, f->det_row[r],
						    f->col0 + (long)k);
			lvl[k] = l->mean[ph[k]];
		}
		/* every column is one read of its channel */
		for (k = 0; k < 4; k++)
			n_ch[ph[k]] += (double)((f->n_cols + 3 - k) / 4);
		i0 = r * f->n_cols;
		if (usual_row(row, a->n + i0, f->n_cols, sat_at,
			      a->n_frames)) {
			welford_usual_row(a->mean + i0, a->m2 + i0, a->n + i0,
					  row, f->n_cols, lvl, inv, inv_next);
			continue;
		}
		for (c = 0; c < f->n_cols; c++) {
			if (row[c] >= sat_at) {
				a->n_sat++;	/* never averaged in (§3.2) */
				continue;
			}
			/* eq. 3.4 (FULL), eq. 3.5 (AMBIENT): L = I - D(t),
			 * per unit t alpha_nd as eq. 3.6 weighs it */
			welford(a, i0 + c, (row[c] - lvl[c & 3]) * inv,
				inv_next);
		}
	}
	for (ch = 0; ch < STRAY_BAYER_CHANNELS; ch++)
		a->dcoef[li][ch] -= n_ch[ch] * inv;
	a->inv_scale_sum += inv;
	a->n_frames++;
	return STRAY_OK;
}

/*
 * stray_accum_var_sums over one piece: blocks of STRAY_LANES pixels all
 * kept and seen in all nf frames add their m2 to usual[] (counted in
 * *n_usual); the others go pixel by pixel to all[], dof[] and kept[].
 */
STRAY_VECTOR_CLONES
static void var_piece(const float *restrict m2, const uint16_t *restrict n,
		      const uint8_t *restrict m, size_t n_pix, unsigned nf,
		      double *restrict usual, size_t *n_usual,
		      double *restrict all, uint64_t *restrict dof,
		      double *restrict kept)
{
	size_t i, k;

	for (i = 0; i + STRAY_LANES <= n_pix; i += STRAY_LANES) {
		unsigned odd = 0;

		for (k = 0; k < STRAY_LANES; k++)
			odd |= (m[i + k] != STRAY_PIX_OK) | (n[i + k] != nf);
		if (!odd) {
			for (k = 0; k < STRAY_LANES; k++)
				usual[k] += m2[i + k];
			*n_usual += STRAY_LANES;
			continue;
		}
		for (k = 0; k < STRAY_LANES; k++)
			if (n[i + k] >= 2) {
				all[k] += m2[i + k];
				dof[k] += n[i + k] - 1u;
				if (m[i + k] == STRAY_PIX_OK)
					kept[k] += m2[i + k] /
						   (n[i + k] - 1.0);
			}
	}
	for (k = 0; i < n_pix; i++, k++)
		if (n[i] >= 2) {
			all[k] += m2[i];
			dof[k] += n[i] - 1u;
			if (m[i] == STRAY_PIX_OK)
				kept[k] += m2[i] / (n[i] - 1.0);
		}
}

void stray_accum_var_sums(const struct stray_accum *a, const uint8_t *mask,
			  struct stray_accum_var *v)
{
	double usual[STRAY_LANES] = { 0 }, all[STRAY_LANES] = { 0 };
	double kept[STRAY_LANES] = { 0 }, u, nf = (double)a->n_frames;
	uint64_t dof[STRAY_LANES] = { 0 }, d = 0;
	size_t i, len, n_usual = 0;
	int k;

	for (i = 0; i < a->n_pix; i += len) {
		const uint8_t *m;

		len = a->n_pix - i;
		m = stray_mask_piece(mask, i, &len);
		var_piece(a->m2 + i, a->n + i, m, len, (unsigned)a->n_frames,
			  usual, &n_usual, all, dof, kept);
	}
	for (k = 0; k < STRAY_LANES; k++)
		d += dof[k];
	/* with one frame there is no m2 (n >= 2 nowhere) */
	u = stray_lanes_total(usual);
	v->m2 = u + stray_lanes_total(all);
	v->dof = (nf >= 2.0 ? (double)n_usual * (nf - 1.0) : 0.0) + (double)d;
	v->kept_var = (nf >= 2.0 ? u / (nf - 1.0) : 0.0) +
		      stray_lanes_total(kept);
}
