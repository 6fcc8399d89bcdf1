/*
 * indi_lab.h - private to rig/indi: the FITS BLOB reader (indi_fits.c).
 */
#ifndef RIG_INDI_LAB_H
#define RIG_INDI_LAB_H

#include "rig/devices.h"

/* The rows of cam out of a FITS file in memory of the window CCD_FRAME
 * was set to (camera.n_cols x the span of camera.rows); *exptime_s = the
 * file's EXPTIME, -1 without one.  RIG_EPROTO names dev. */
int rig_indi_fits_image(const unsigned char *data, size_t len,
			const struct rig_camera_cfg *cam, const char *dev,
			struct rig_image *img, double *exptime_s,
			struct rig_error *err);

#endif /* RIG_INDI_LAB_H */
