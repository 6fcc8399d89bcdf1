/*
 * response.c - the true stray-light response J = L_ful/(t1 alpha_nd1) -
 * L_amb/(t2 alpha_nd2) of one angle (thesis eq. 3.6, 3.8), its sums
 * P (eq. 3.9), Pbar (eq. 3.13) and sigma (eq. 3.14), and the propagated
 * variance of P.
 */
#include <math.h>

#include "stray/reduce_response.h"

/* The sums of pooled_var for two groups in one pass (four independent
 * chains of additions instead of two after two; each in pixel order, so
 * the same sums). */
static void pooled_sums(const struct stray_accum *a,
			const struct stray_accum *b, double *sum)
{
	double na = 0.0, da = 0.0, nb = 0.0, db = 0.0;
	size_t i;

	for (i = 0; i < a->n_pix; i++) {
		if (a->n[i] >= 2) {
			na += a->m2[i];
			da += a->n[i] - 1.0;
		}
		if (b->n[i] >= 2) {
			nb += b->m2[i];
			db += b->n[i] - 1.0;
		}
	}
	sum[0] = na;
	sum[1] = da;
	sum[2] = nb;
	sum[3] = db;
}

/* Single-frame variance of a rate, pooled over pixels with repeats
 * (num, den: the sums of pooled_sums). */
static double pooled_var(const struct stray_accum *a,
			 const struct stray_dark_model *d, double num,
			 double den)
{
	double v = 0.0, k;
	size_t l;
	unsigned ch;

	if (den > 0.0)
		return num / den;
	/* One frame only: read and dark noise of the darks, a lower bound. */
	for (l = 0, den = 0.0; l < d->n; l++)
		for (ch = 0; ch < STRAY_BAYER_CHANNELS; ch++)
			if (a->dcoef[l][ch] != 0.0) {
				v += d->lvl[l].var[ch];
				den += 1.0;
			}
	k = a->n_frames ? a->inv_scale_sum / a->n_frames : 0.0;
	return den > 0.0 ? v / den * k * k : 0.0;
}

/* Variance of one pixel's temporal mean. */
static double mean_var(const struct stray_accum *a, size_t i, double pooled)
{
	double n = a->n[i];

	return n >= 2 ? a->m2[i] / (n * (n - 1.0)) : pooled / n;
}

/* Variance of P from the dark levels, shared by all pixels of a channel. */
static double dark_var(const struct stray_accum *full,
		       const struct stray_accum *amb,
		       const struct stray_dark_model *d)
{
	double v = 0.0;
	size_t l;
	unsigned ch;

	for (l = 0; l < d->n; l++)
		for (ch = 0; ch < STRAY_BAYER_CHANNELS; ch++) {
			double g = full->dcoef[l][ch] / full->n_frames -
				   amb->dcoef[l][ch] / amb->n_frames;

			v += g * g * d->lvl[l].var_mean[ch];
		}
	return v;
}

/*
 * Fill invalid pixels (var_j < 0) of one row from the nearest valid pixels
 * of the same colour, 2k columns away (k = 1..8), else leave J = 0.
 */
static size_t fill_row(float *j, float *var_j, size_t n_cols)
{
	size_t c, k, unfilled = 0;

	for (c = 0; c < n_cols; c++) {
		double s = 0.0, vs = 0.0;
		int m = 0;

		if (var_j[c] >= 0.0f)
			continue;
		for (k = 2; k <= 16 && m == 0; k += 2) {
			if (c >= k && var_j[c - k] >= 0.0f) {
				s += j[c - k];
				vs += var_j[c - k];
				m++;
			}
			if (c + k < n_cols && var_j[c + k] >= 0.0f) {
				s += j[c + k];
				vs += var_j[c + k];
				m++;
			}
		}
		if (m == 0) {
			unfilled++;
			j[c] = 0.0f;
			continue;
		}
		j[c] = (float)(s / m);
		/* Marked filled (not valid): negative, -(var + 1). */
		var_j[c] = (float)(-(vs / m) - 1.0);
	}
	return unfilled;
}

/* 3-pixel row-neighbour mean (§3.2), in place with a one-pixel lag. */
static void row_filter(float *j, size_t n_cols)
{
	double prev = j[0];
	size_t c;

	for (c = 0; c < n_cols; c++) {
		double cur = j[c], s = cur, m = 1.0;

		if (c > 0) {
			s += prev;
			m += 1.0;
		}
		if (c + 1 < n_cols) {
			s += j[c + 1];
			m += 1.0;
		}
		prev = cur;
		j[c] = (float)(s / m);
	}
}

static void per_pixel_j(const struct stray_accum *full,
			const struct stray_accum *amb, const uint8_t *mask,
			double pool_f, double pool_a, float *j, float *var_j,
			struct stray_response_sums *out)
{
	size_t i;

	for (i = 0; i < full->n_pix; i++) {
		if (mask && mask[i] != STRAY_PIX_OK) {
			out->n_masked++;
			var_j[i] = -1.0f;
			continue;
		}
		if (full->n[i] == 0 || amb->n[i] == 0) {
			out->n_sat_pix++;
			var_j[i] = -1.0f;
			continue;
		}
		/* eq. 3.6: true response J_i */
		j[i] = full->mean[i] - amb->mean[i];
		var_j[i] = (float)(mean_var(full, i, pool_f) +
				   mean_var(amb, i, pool_a));
		out->n_valid++;
	}
}

int stray_response_compute(const struct stray_accum *full,
			   const struct stray_accum *amb,
			   const struct stray_dark_model *d,
			   const uint8_t *mask, const struct stray_frame *geo,
			   const struct stray_response_opts *o, float *j,
			   float *var_j, struct stray_response_sums *out,
			   struct stray_error *err)
{
	size_t n = geo->n_rows * geo->n_cols, i, r;
	double p = 0.0, vp = 0.0, s2 = 0.0, sum[4];

	if (full->n_pix != n || amb->n_pix != n)
		return stray_error_set(err, STRAY_EINVAL, "NAXIS",
				       "groups differ in frame size");
	if (full->n_frames == 0 || amb->n_frames == 0)
		return stray_error_set(err, STRAY_ENOTFOUND, "FRAMETYP",
			full->n_frames ? "no AMBIENT frame at this angle"
				       : "no FULL frame at this angle");
	out->n_pix = n;
	out->n_valid = out->n_masked = out->n_sat_pix = 0;
	pooled_sums(full, amb, sum);
	per_pixel_j(full, amb, mask, pooled_var(full, d, sum[0], sum[1]),
		    pooled_var(amb, d, sum[2], sum[3]), j, var_j, out);
	for (r = 0; r < geo->n_rows; r++) {
		size_t off = r * geo->n_cols;

		fill_row(j + off, var_j + off, geo->n_cols);
		if (o && o->row_filter)
			row_filter(j + off, geo->n_cols);
	}
	for (i = 0; i < n; i++) {
		if (var_j[i] < 0.0f)	/* filled: its neighbours' variance */
			var_j[i] = var_j[i] <= -1.0f ? -var_j[i] - 1.0f : 0.0f;
		p += j[i];	/* eq. 3.9: P = sum_i J_i */
		vp += var_j[i];
	}
	out->power = p;
	out->var_power = vp + dark_var(full, amb, d);
	out->mean = p / (double)n;	/* eq. 3.13 */
	for (i = 0; i < n; i++)
		s2 += (j[i] - out->mean) * (j[i] - out->mean);
	out->sigma = sqrt(s2 / (double)n);	/* eq. 3.14 */
	return STRAY_OK;
}

void stray_response_profile(const float *j, const float *var_j,
			    size_t n_rows, size_t n_cols, double *profile,
			    double *var_profile)
{
	size_t r, c;

	for (c = 0; c < n_cols; c++)
		profile[c] = var_profile[c] = 0.0;
	for (r = 0; r < n_rows; r++)	/* row by row: memory order */
		for (c = 0; c < n_cols; c++) {
			profile[c] += j[r * n_cols + c];
			var_profile[c] += var_j[r * n_cols + c];
		}
	for (c = 0; c < n_cols; c++) {
		profile[c] /= (double)n_rows;
		var_profile[c] /= (double)n_rows * (double)n_rows;
	}
}
