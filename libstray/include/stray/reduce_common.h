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

/* The frame totals S_k of one group and their places x_k in the
 * acquisition order (sums shifted by the first, for precision). */
struct stray_common_group {
	size_t n;
	double s0, x0;		/* the first total and place */
	double ss, sss, sx, sxx, sxs;	/* sums of S', S'^2, x', x'^2, x'S' */
	double v_ind;		/* sum_i var(L_i): independent pixels */
	int incomplete;		/* a sample saturated: totals not comparable */
};

void stray_common_group_reset(struct stray_common_group *g);

/* Add one frame's total over the unmasked pixels (mask may be NULL),
 * taken at place x in the acquisition order. */
int stray_common_group_add(struct stray_common_group *g,
			   const struct stray_dark_model *d,
			   const struct stray_frame *f, const uint8_t *mask,
			   double x, struct stray_error *err);

/* Close a group with the variance sums of its accumulator (the same
 * frames and mask: stray_accum_var_sums, or a response's var[]): what
 * independent pixels give to the scatter of its totals. */
void stray_common_group_finish(struct stray_common_group *g,
			       const struct stray_accum_var *v);

/* The mean total of a closed group. */
double stray_common_group_mean(const struct stray_common_group *g);

/*
 * A closed group's excess relative variance *est = (var_S - var_ind) /
 * Sbar^2 and *ind = var_ind / Sbar^2, with the totals first detrended by
 * a source drifting by the fraction beta per unit of place (the sweep's
 * fitted drift: a known change, not noise).  Returns the degrees of
 * freedom, n - 1 (0: unusable, fewer than 2 frames or a saturated
 * sample).
 */
size_t stray_common_group_stats(const struct stray_common_group *g,
				double beta, double *est, double *ind);

/*
 * The relative variance s^2 per frame pooled over n groups, each
 * weighted by the inverse variance of its estimate, dof / (s^2 + ind)^2
 * (iterated); 0 when none is seen.
 */
double stray_common_fit(const double *est, const double *ind,
			const size_t *dof, size_t n);

#endif /* STRAY_REDUCE_COMMON_H */
