/*
 * reduce_response.h - the true stray-light response J of one angle
 * (thesis §3.2, eq. 3.4-3.6, 3.8) and its sums (eq. 3.9, 3.13-3.14).
 *
 * Frames of a group (FULL or AMBIENT at one angle) are streamed into a
 * per-pixel accumulator of the light rate L / (t_exp alpha_nd monitor)
 * (eq. 3.4-3.5 with the dark level of the matching exposure); pixels at or
 * above SATLEVEL are left out of that frame's update and counted.  The two
 * groups then give J = rate_full - rate_amb (eq. 3.6), the temporal mean of
 * the repeated frames, with the variance of each pixel's mean from its
 * scatter over the repeats (shot, read and dark noise together) and the
 * dark levels' own uncertainty propagated.  No heap: caller buffers.
 */
#ifndef STRAY_REDUCE_RESPONSE_H
#define STRAY_REDUCE_RESPONSE_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"
#include "stray/reduce_dark.h"
#include "stray/reduce_frame.h"

/* Per-pixel temporal mean and scatter of the light rate of one group. */
struct stray_accum {
	size_t n_pix;
	float *mean;		/* n_pix: rate, counts/s */
	float *m2;		/* n_pix: Welford sum of squares */
	uint16_t *n;		/* n_pix: frames used */
	unsigned long n_frames;
	unsigned long n_sat;	/* saturated samples left out */
	double inv_scale_sum;	/* sum of 1 / (t_exp alpha_nd monitor) */
	/* d rate_mean / d D_l,c summed over frames, per dark level */
	double dcoef[STRAY_DARK_LEVELS_MAX][STRAY_BAYER_CHANNELS];
};

/* Bytes of caller memory one accumulator of n_pix pixels needs. */
size_t stray_accum_bytes(size_t n_pix);

/* Lay the accumulator over mem (stray_accum_bytes(n_pix) bytes, aligned). */
void stray_accum_init(struct stray_accum *a, size_t n_pix, void *mem);

/* Zero for a new group. */
void stray_accum_reset(struct stray_accum *a);

/* eq. 3.4-3.5: add one frame's light rate (I - D(t)) / (t alpha_nd m). */
int stray_accum_add(struct stray_accum *a, const struct stray_dark_model *d,
		    const struct stray_frame *f, struct stray_error *err);

/* An accumulator's variance sums: m2 and n - 1 over its pixels with
 * repeats (n >= 2), whose ratio is the single-frame variance pooled over
 * pixels, and m2 / (n - 1) over those of them a mask keeps: the pixels'
 * own variances summed over the frame (reduce_common.h's v_ind). */
struct stray_accum_var {
	double m2, dof;
	double kept_var;
};

/* One pass over a's pixels; mask may be NULL (every pixel kept). */
void stray_accum_var_sums(const struct stray_accum *a, const uint8_t *mask,
			  struct stray_accum_var *v);

struct stray_response_opts {
	int row_filter;		/* 3-pixel row-neighbour mean (§3.2) */
};

/* The sums of one angle's J image. */
struct stray_response_sums {
	size_t n_pix;		/* n_ppi */
	size_t n_valid;		/* pixels measured (not masked, not sat) */
	size_t n_masked;	/* hot or dead: filled from row neighbours */
	size_t n_sat_pix;	/* saturated in every frame: filled too */
	double power;		/* eq. 3.9: P = sum_i J_i */
	double var_power;	/* its variance (noise + dark levels) */
	double mean;		/* eq. 3.13: P / n_ppi */
	double sigma;		/* eq. 3.14: image standard deviation */
	struct stray_accum_var var[2];	/* of FULL [0] and AMBIENT [1] */
};

/*
 * eq. 3.6: J = rate_full - rate_amb per pixel into j (n_pix floats) and
 * var_j (n_pix floats, variance of J_i).  Pixels flagged in mask, or with
 * no unsaturated frame in a group, are filled from the nearest valid pixels
 * of the same colour (two columns away) on the same row.
 */
int stray_response_compute(const struct stray_accum *full,
			   const struct stray_accum *amb,
			   const struct stray_dark_model *d,
			   const uint8_t *mask, const struct stray_frame *geo,
			   const struct stray_response_opts *o, float *j,
			   float *var_j, struct stray_response_sums *out,
			   struct stray_error *err);

/*
 * Row-collapsed profile (fig. 3.9): mean of J over stored rows per column
 * into profile[n_cols], its variance into var_profile[n_cols].
 */
void stray_response_profile(const float *j, const float *var_j,
			    size_t n_rows, size_t n_cols, double *profile,
			    double *var_profile);

#endif /* STRAY_REDUCE_RESPONSE_H */
