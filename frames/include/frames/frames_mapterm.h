/*
 * frames_mapterm.h - mapped stray light in the models of `stray frames`
 * (issue 28): the part of the focal map's shape the detectors' tile
 * background cannot follow, as the background-error term of
 * stray/detector.h (bg_resid_rel, detector.c's eq. R), and the false-star
 * rates of the window and threshold detectors with it.
 */
#ifndef STRAY_FRAMES_FRAMES_MAPTERM_H
#define STRAY_FRAMES_FRAMES_MAPTERM_H

#include "frames/frames_run.h"

/*
 * rms over the cols x rows lit pixels of (w - w^) / w, w the map's
 * weights, w^ what frames_detect's background makes of them: the tile_px
 * tiles' means, bilinear between tile centres, extrapolated.  A linear
 * ramp gives 0 (the bilinear follows it); curvature and steps at the
 * tiles' scale do not.  0 for a NULL map.
 */
double frames_map_resid_rel(const float *w, int cols, int rows, int tile_px);

/*
 * False stars per frame of the window detector (where its window fits)
 * and of the threshold detector, through stray/detector.h with the
 * background-error term resid_rel (the thresholds fm's).
 */
int frames_mapterm_rates(const struct frames_model *fm, double resid_rel,
			 double *window, double *threshold,
			 struct stray_error *err);

#endif /* STRAY_FRAMES_FRAMES_MAPTERM_H */
