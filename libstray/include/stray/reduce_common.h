/*
 * reduce_common.h - noise common to every pixel of a frame (beyond the
 * thesis): what scales a whole frame at once, chiefly the lamp monitor's
 * read noise (each frame is divided by its own MONITOR reading, eq. 3.6),
 * but also lamp flicker or exposure-time jitter.  Per-pixel variances
 * summed over the image (eq. 3.9) treat pixels as independent and miss
 * it: a relative scatter s per frame adds s^2 P^2 / n_frames to var(P),
 * while it adds only s^2 J_i^2 to each pixel.
 *
 * It is measured from the data: over the repeats of each group the
 * scatter of the frame totals S_k = sum_i L_k,i / (t alpha_nd m_k)
 * (eq. 3.4-3.5) is compared with what the pixels' own variances give;
 * the excess, pooled over every group of the sweep, is s^2.
 */
#ifndef STRAY_REDUCE_COMMON_H
#define STRAY_REDUCE_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include "stray/reduce_response.h"

/* The frame totals of one group (Welford), and whether any was cut. */
struct stray_common_group {
	size_t n;
	double mean, m2;
	int incomplete;		/* a sample saturated: totals not comparable */
};

/* Pooled excess over the groups: sum (n-1)(var_S - var_ind), and
 * sum (n-1) mean_S^2. */
struct stray_common_pool {
	double num, den;
	size_t n_groups, dof;
};

void stray_common_group_reset(struct stray_common_group *g);

/* Add one frame's total over the unmasked pixels (mask may be NULL). */
int stray_common_group_add(struct stray_common_group *g,
			   const struct stray_dark_model *d,
			   const struct stray_frame *f, const uint8_t *mask,
			   struct stray_error *err);

/* Pool a finished group, given its accumulator (the same frames). */
void stray_common_pool_add(struct stray_common_pool *p,
			   const struct stray_common_group *g,
			   const struct stray_accum *a, const uint8_t *mask);

/* The relative variance s^2 per frame (0 when none is seen). */
double stray_common_rel_var(const struct stray_common_pool *p);

#endif /* STRAY_REDUCE_COMMON_H */
