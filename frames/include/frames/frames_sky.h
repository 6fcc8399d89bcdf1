/*
 * frames_sky.h - `stray frames --catalogue CAT --attitude q` (issue 24):
 * the real sky's stars through the head's camera, with their colours in
 * the sensor's passband, and the list of every star rendered
 * (--truth-stars) so other star-tracker software can be scored on the
 * frames.
 */
#ifndef STRAY_FRAMES_FRAMES_SKY_H
#define STRAY_FRAMES_FRAMES_SKY_H

#include <stddef.h>

#include "stray/catalogue.h"
#include "stray/error.h"
#include "stray/sensor.h"

/*
 * The stars of catalogue path (stray/starcat.h) brighter than mag_max
 * (V) at epoch_jyear, through the camera of attitude q_ib whose frame is
 * cols x rows from detector pixel (col0, row0): positions, V and
 * photo-electrons f0_e 10^(-0.4 V) c(B-V) (stray/colour.h, the sensor's
 * QE).  *n written (at most max).
 */
int frames_sky_stars(const char *path, const struct stray_sensor *s,
		     const double q_ib[4], double epoch_jyear, int col0,
		     int row0, int cols, int rows, double mag_max, double f0_e,
		     struct stray_star *out, size_t max, size_t *n,
		     struct stray_error *err);

/* T.csv: frame,x_px,y_px,v_mag,electrons - every star of every frame
 * (the same stars in each: one attitude). */
int frames_sky_truth_write(const char *path, const struct stray_star *st,
			   size_t n, int frames, struct stray_error *err);

#endif /* STRAY_FRAMES_FRAMES_SKY_H */
