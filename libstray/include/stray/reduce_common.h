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

void stray_common_group_reset(struct stray_common_group *g);

/* Add one frame's total over the unmasked pixels (mask may be NULL). */
int stray_common_group_add(struct stray_common_group *g,
			   const struct stray_dark_model *d,
			   const struct stray_frame *f, const uint8_t *mask,
			   struct stray_error *err);

/*
 * A finished group, given its accumulator (the same frames): *est, the
 * excess relative variance of its frame totals (var_S - var_ind) / S^2,
 * and *ind, var_ind / S^2, what independent pixels give.  Returns its
 * degrees of freedom, n - 1 (0: unusable, fewer than 2 frames or a
 * saturated sample).
 */
size_t stray_common_group_stats(const struct stray_common_group *g,
				const struct stray_accum *a,
				const uint8_t *mask, double *est,
				double *ind);

/*
 * The relative variance s^2 per frame pooled over n groups, each
 * weighted by the inverse variance of its estimate, dof / (s^2 + ind)^2
 * (iterated); 0 when none is seen.
 */
double stray_common_fit(const double *est, const double *ind,
			const size_t *dof, size_t n);

#endif /* STRAY_REDUCE_COMMON_H */
