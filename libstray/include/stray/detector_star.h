/*
 * detector_star.h - a star's detection under a background: the lost-star model
 * of each detector (libstray/core/detector_star.c).
 * Freestanding C99, no heap (stray/detector.h includes it).
 */
#ifndef STRAY_DETECTOR_STAR_H
#define STRAY_DETECTOR_STAR_H

#include "stray/detector_types.h"
#include "stray/error.h"

/*
 * Probability that a star of star_e photo-electrons at a uniformly random
 * place is detected at attenuation alpha (averaged over the map's regions
 * and over the star's place within a pixel).
 */
int stray_detector_star_prob(const struct stray_detector *d,
			     const struct stray_fdr_model *m, stray_real alpha,
			     stray_real star_e, stray_real *p,
			     struct stray_error *err);

/* The photons a star needs to be detected with probability pr at alpha
 * (the limiting magnitude's flux); STRAY_ERANGE beyond 1e12 e-. */
int stray_detector_limiting_e(const struct stray_detector *d,
			      const struct stray_fdr_model *m,
			      stray_real alpha, stray_real pr,
			      stray_real *star_e, struct stray_error *err);

/* The WINDOW model's positions near a star: offsets of pixel centres from
 * the star's pixel within sqrt(5) px; returns their number. */
unsigned stray_detector_positions(int dx[STRAY_DET_POS_MAX],
				  int dy[STRAY_DET_POS_MAX]);

#endif /* STRAY_DETECTOR_STAR_H */
