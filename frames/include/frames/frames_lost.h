/*
 * frames_lost.h - lost stars on rendered frames (issue 28): the fraction
 * of true stars each OpenCV detector of `stray frames` finds, per
 * magnitude bin, beside the lost-star model of stray/detector.h for the
 * same detector (thesis window sum: WINDOW; threshold: THRESHOLD).
 */
#ifndef STRAY_FRAMES_FRAMES_LOST_H
#define STRAY_FRAMES_FRAMES_LOST_H

#include "frames/frames_run.h"
#include "stray/detector.h"

#define FRAMES_LOST_BINS 20	/* 0.1 mag from m = 4.8 */
#define FRAMES_LOST_MAG0 4.8
#define FRAMES_LOST_STEP 0.1
#define FRAMES_LOST_CACHE 200	/* model cached per 0.02 mag */

struct frames_lost {
	struct stray_detector det[2];	/* window, threshold */
	struct stray_fdr_model m;
	double alpha_eff;
	long n[FRAMES_LOST_BINS], found[2][FRAMES_LOST_BINS];
	double model[2][FRAMES_LOST_BINS];	/* sum over stars */
	double cache[2][FRAMES_LOST_CACHE];	/* NaN: not yet */
};

/* The models for the frame's nominal model and detector thresholds. */
int frames_lost_init(struct frames_lost *l, const struct frames_model *fm,
		     struct stray_error *err);

/* One frame: which stars each detector found (a detection within match
 * px: the window's radius, 4 px for the threshold detector). */
void frames_lost_add(struct frames_lost *l,
		     const struct frames_detect_out out[2],
		     const double match[2], const struct stray_star *stars,
		     size_t n_stars);

#endif /* STRAY_FRAMES_FRAMES_LOST_H */
