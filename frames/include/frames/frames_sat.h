/*
 * frames_sat.h - frames the models cannot speak for: stray light that
 * fills the 12-bit ADC (issue 28).  A clipped pixel has no upward noise
 * (no false stars) and no room for a star's light (no stars), so a frame
 * of white pixels "agrees" with any small model rate by saying nothing.
 * The check refuses a run whose every pixel clips and flags one where
 * some do; a refusal beats a wrong answer.
 */
#ifndef STRAY_FRAMES_FRAMES_SAT_H
#define STRAY_FRAMES_FRAMES_SAT_H

#include <stddef.h>

#include "frames/frames_run.h"

/* The background's noise tail that must stay below full scale. */
#define FRAMES_SAT_SIGMAS 5.0
/* Fraction of clipping pixels above which no verdict is given. */
#define FRAMES_SAT_FLAG 1e-3

/*
 * Fraction of the n rendered pixels whose background (the model's mean
 * stray e- times weight[i], or uniform when weight is NULL, plus dark
 * current) lies within FRAMES_SAT_SIGMAS of the ADC's full scale.
 * STRAY_EINVAL (field "alpha", value alpha) when that is every pixel.
 */
int frames_saturation(const struct frames_model *fm, const float *weight,
		      size_t n, double alpha, double *clip_frac,
		      struct stray_error *err);

/* The verdict that replaces "agree"/"disagree" when clip_frac is above
 * FRAMES_SAT_FLAG; returns 1 when it wrote one. */
int frames_saturation_verdict(double clip_frac, char *text, size_t size);

#endif /* STRAY_FRAMES_FRAMES_SAT_H */
