/*
 * detector_blob.h - THRESHOLD's lost stars as 8-connected components (lattice
 * animals; libstray/core/detector_blob.c).
 * Freestanding C99, no heap (stray/detector.h includes it).
 */
#ifndef STRAY_DETECTOR_BLOB_H
#define STRAY_DETECTOR_BLOB_H

#include "stray/detector_types.h"
#include "stray/error.h"

/* THRESHOLD's animals for d->min_px (n_animal 0 past
 * STRAY_DET_BLOB_PX_MAX); called by stray_detector_setup. */
int stray_detector_blob_setup(struct stray_detector *d,
			      struct stray_error *err);

/* THRESHOLD: the chance that the 8-connected component of pixels above
 * d->pixel_t_e through one of the four pixels nearest a star of star e-
 * at (ox, oy) in [0, 1/2)^2 from pixel (0, 0)'s centre has >= min_px
 * pixels, under background variance b. */
stray_real stray_detector_blob_prob(const struct stray_detector *d,
				    stray_real b, stray_real star,
				    stray_real ox, stray_real oy, stray_real t);

#endif /* STRAY_DETECTOR_BLOB_H */
