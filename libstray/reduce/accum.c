/*
 * accum.c - the temporal mean of the repeated frames of one group (thesis
 * §3.2: 3 consecutive frames averaged), as light rates
 * (I - D(t)) / (t_exp alpha_nd monitor) (eq. 3.4-3.6), saturated samples
 * left out and counted.
 */
#include <string.h>

#include "stray/reduce_response.h"

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

int stray_accum_add(struct stray_accum *a, const struct stray_dark_model *d,
		    const struct stray_frame *f, struct stray_error *err)
{
	double n_ch[STRAY_BAYER_CHANNELS] = { 0 };
	const struct stray_dark_level *l;
	double inv, inv_next;
	size_t r, c, li;
	unsigned ch;
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
		for (c = 0; c < f->n_cols; c++) {
			n_ch[ph[c & 3]] += 1.0;
			if ((long)row[c] >= f->sat_level) {
				a->n_sat++;	/* never averaged in (§3.2) */
				continue;
			}
			/* eq. 3.4 (FULL), eq. 3.5 (AMBIENT): L = I - D(t),
			 * per unit t alpha_nd as eq. 3.6 weighs it */
			welford(a, r * f->n_cols + c, (row[c] - lvl[c & 3]) * inv,
				inv_next);
		}
	}
	for (ch = 0; ch < STRAY_BAYER_CHANNELS; ch++)
		a->dcoef[li][ch] -= n_ch[ch] * inv;
	a->inv_scale_sum += inv;
	a->n_frames++;
	return STRAY_OK;
}
