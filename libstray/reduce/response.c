/*
 * response.c - the true stray-light response J = L_ful/(t1 alpha_nd1) -
 * L_amb/(t2 alpha_nd2) of one angle (thesis eq. 3.6, 3.8), its sums
 * P (eq. 3.9), Pbar (eq. 3.13) and sigma (eq. 3.14), and the propagated
 * variance of P.
 */
#include <math.h>

#include "stray/reduce_response.h"
#include "pixel_sums.h"

/* Single-frame variance of a rate, pooled over pixels with repeats
 * (num, den: their m2 and n - 1 summed, stray_accum_var_sums). */
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

/* var of the temporal mean of a pixel seen in all of a's frames: m2 cm
 * + cp (mean_var with n = n_frames, the division taken once). */
static void usual_var(const struct stray_accum *a, double pooled, double *cm,
		      double *cp)
{
	double n = (double)a->n_frames;

	*cm = n >= 2.0 ? 1.0 / (n * (n - 1.0)) : 0.0;
	*cp = n >= 2.0 ? 0.0 : pooled / n;
}

/* Whether pixels [i, i + n) are all unmasked and seen in every frame of
 * both groups (an OR over the row the compiler vectorises). */
STRAY_VECTOR_CLONES
static int usual_pixels(const struct stray_accum *full,
			const struct stray_accum *amb, const uint8_t *mask,
			size_t i, size_t n)
{
	const uint16_t *restrict nf = full->n + i, *restrict na = amb->n + i;
	unsigned odd = 0, f = (unsigned)full->n_frames;
	unsigned g = (unsigned)amb->n_frames;
	size_t c;

	for (c = 0; c < n; c++)
		odd |= (nf[c] != f) | (na[c] != g);
	if (mask)
		for (c = 0; c < n; c++)
			odd |= mask[i + c] != STRAY_PIX_OK;
	return !odd;
}

/* eq. 3.6 over a usual row: J_i and its variance, without branches. */
STRAY_VECTOR_CLONES
static void usual_j(const float *restrict fm, const float *restrict fm2,
		    const float *restrict am, const float *restrict am2,
		    size_t n, const double *coef, float *restrict j,
		    float *restrict var_j)
{
	size_t c;

	for (c = 0; c < n; c++) {
		j[c] = fm[c] - am[c];
		var_j[c] = (float)((fm2[c] * coef[0] + coef[1]) +
				   (am2[c] * coef[2] + coef[3]));
	}
}

/* eq. 3.6 for the row of pixels [r, r + n_cols); coef: usual_var of
 * both groups.  Returns the number of pixels marked invalid (var_j -1),
 * for fill_row. */
static size_t j_row(const struct stray_accum *full, const struct stray_accum *amb,
		  const uint8_t *mask, size_t r, size_t n_cols,
		  const double *coef, double pool_f, double pool_a, float *j,
		  float *var_j, struct stray_response_sums *out)
{
	size_t i, invalid = 0;

	if (usual_pixels(full, amb, mask, r, n_cols)) {
		usual_j(full->mean + r, full->m2 + r, amb->mean + r,
			amb->m2 + r, n_cols, coef, j + r, var_j + r);
		out->n_valid += n_cols;
		return 0;
	}
	for (i = r; i < r + n_cols; i++) {
		if (mask && mask[i] != STRAY_PIX_OK) {
			out->n_masked++;
			var_j[i] = -1.0f;
			invalid++;
			continue;
		}
		if (full->n[i] == 0 || amb->n[i] == 0) {
			out->n_sat_pix++;
			var_j[i] = -1.0f;
			invalid++;
			continue;
		}
		/* eq. 3.6: true response J_i */
		j[i] = full->mean[i] - amb->mean[i];
		var_j[i] = (float)(mean_var(full, i, pool_f) +
				   mean_var(amb, i, pool_a));
		out->n_valid++;
	}
	return invalid;
}

/* A variance as fill_row left it: filled pixels (var_j <= -1) take
 * their neighbours' variance, var_j -(v + 1); unfilled ones 0. */
static inline float filled_var(float v)
{
	return v >= 0.0f ? v : v <= -1.0f ? -v - 1.0f : 0.0f;
}

/* eq. 3.9 over one row, into lanes: P = sum_i J_i and the sum of
 * var J_i. */
STRAY_VECTOR_CLONES
static void power_row(const float *restrict j, float *restrict var_j,
		      size_t n, double *restrict lp, double *restrict lv)
{
	size_t i, k;

	for (i = 0; i + STRAY_LANES <= n; i += STRAY_LANES)
		for (k = 0; k < STRAY_LANES; k++) {
			var_j[i + k] = filled_var(var_j[i + k]);
			lp[k] += j[i + k];
			lv[k] += var_j[i + k];
		}
	for (k = 0; i < n; i++, k++) {
		var_j[i] = filled_var(var_j[i]);
		lp[k] += j[i];
		lv[k] += var_j[i];
	}
}

/* sum_i (J_i - mean)^2, for eq. 3.14 */
STRAY_VECTOR_CLONES
static double spread(const float *j, size_t n, double mean)
{
	double l[STRAY_LANES] = { 0 };
	size_t i, k;

	for (i = 0; i + STRAY_LANES <= n; i += STRAY_LANES)
		for (k = 0; k < STRAY_LANES; k++)
			l[k] += (j[i + k] - mean) * (j[i + k] - mean);
	for (k = 0; i < n; i++, k++)
		l[k] += (j[i] - mean) * (j[i] - mean);
	return stray_lanes_total(l);
}

int stray_response_compute(const struct stray_accum *full,
			   const struct stray_accum *amb,
			   const struct stray_dark_model *d,
			   const uint8_t *mask, const struct stray_frame *geo,
			   const struct stray_response_opts *o, float *j,
			   float *var_j, struct stray_response_sums *out,
			   struct stray_error *err)
{
	size_t n = geo->n_rows * geo->n_cols, r;
	double lp[STRAY_LANES] = { 0 }, lv[STRAY_LANES] = { 0 };
	double p, vp, coef[4], pool_f, pool_a;

	if (full->n_pix != n || amb->n_pix != n)
		return stray_error_set(err, STRAY_EINVAL, "NAXIS",
				       "groups differ in frame size");
	if (full->n_frames == 0 || amb->n_frames == 0)
		return stray_error_set(err, STRAY_ENOTFOUND, "FRAMETYP",
			full->n_frames ? "no AMBIENT frame at this angle"
				       : "no FULL frame at this angle");
	out->n_pix = n;
	out->n_valid = out->n_masked = out->n_sat_pix = 0;
	stray_accum_var_sums(full, mask, &out->var[0]);
	stray_accum_var_sums(amb, mask, &out->var[1]);
	pool_f = pooled_var(full, d, out->var[0].m2, out->var[0].dof);
	pool_a = pooled_var(amb, d, out->var[1].m2, out->var[1].dof);
	usual_var(full, pool_f, &coef[0], &coef[1]);
	usual_var(amb, pool_a, &coef[2], &coef[3]);
	/* row by row, each row's steps while it is in cache */
	for (r = 0; r < n; r += geo->n_cols) {
		if (j_row(full, amb, mask, r, geo->n_cols, coef, pool_f,
			  pool_a, j, var_j, out))
			fill_row(j + r, var_j + r, geo->n_cols);
		if (o && o->row_filter)
			row_filter(j + r, geo->n_cols);
		power_row(j + r, var_j + r, geo->n_cols, lp, lv);
	}
	p = stray_lanes_total(lp);
	vp = stray_lanes_total(lv);
	out->power = p;
	out->var_power = vp + dark_var(full, amb, d);
	out->mean = p / (double)n;	/* eq. 3.13 */
	out->sigma = sqrt(spread(j, n, out->mean) / (double)n); /* eq. 3.14 */
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
