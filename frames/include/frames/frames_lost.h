/*
 * frames_lost.h - lost stars on rendered frames (issue 28): the fraction
 * of true stars each OpenCV detector of `stray frames` finds, per
 * magnitude bin, beside the lost-star model of stray/detector.h for the
 * same detector (thesis window sum: WINDOW; threshold: THRESHOLD): the
 * model as each frame sets the detectors (frames_adc.h: their background
 * and the ADC's steps), and the nominal one (the sensor's, as `stray fdr`
 * has it) beside it.
 */
#ifndef STRAY_FRAMES_FRAMES_LOST_H
#define STRAY_FRAMES_FRAMES_LOST_H

#include "frames/frames_adc.h"
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
	double model[2][FRAMES_LOST_BINS];	/* sum over stars: this frame's */
	double nominal[2][FRAMES_LOST_BINS];	/* the sensor's model */
	struct frames_adc adc;			/* the frame's background */
	double cache[2][FRAMES_LOST_CACHE];	/* NaN: not yet */
};

/* The models for the frame's nominal model and detector thresholds. */
int frames_lost_init(struct frames_lost *l, const struct frames_model *fm,
		     struct stray_error *err);

/* The frame's background as the detectors estimated it (tiles_x x
 * tiles_y tiles of tile_px, frames_detect's bg_tiles; the buffer is read
 * by the next frames_lost_add) and the known map (NULL: uniform). */
void frames_lost_set_frame(struct frames_lost *l, const float *tiles,
			   int tiles_x, int tiles_y, int tile_px,
			   const float *weight, int cols, int rows);

/* One frame: which stars each detector found (window: a region of
 * above-threshold windows reaching within match[0] px, FRAMES_REACH_PX;
 * threshold: a centroid within match[1] px, 4). */
void frames_lost_add(struct frames_lost *l,
		     const struct frames_detect_out out[2],
		     const double match[2], const struct stray_star *stars,
		     size_t n_stars);

#endif /* STRAY_FRAMES_FRAMES_LOST_H */
