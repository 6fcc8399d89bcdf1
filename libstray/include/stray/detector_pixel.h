/*
 * detector_pixel.h - what every detector model shares at the pixel level
 * (libstray/core/detector_pixel.c).
 * Freestanding C99, no heap (stray/detector.h includes it).
 */
#ifndef STRAY_DETECTOR_PIXEL_H
#define STRAY_DETECTOR_PIXEL_H

#include "stray/detector_types.h"

/* Variance of one pixel's count at attenuation alpha: I_px + read^2 +
 * dark t (the model's detector noise; zero for the bare thesis). */
stray_real stray_detector_pixel_var(const struct stray_fdr_model *m,
				    stray_real alpha);

/* Fraction of a star's photons (Gaussian PSF of sigma s, pixel-
 * integrated) in pixel (i, j), the star at (ox, oy) from pixel (0, 0)'s
 * centre. */
stray_real stray_detector_psf_pixel(stray_real s, stray_real ox,
				    stray_real oy, int i, int j);

/* TETRA3's threshold above the background at alpha, e-. */
stray_real stray_detector_tetra3_threshold(const struct stray_detector *d,
					   const struct stray_fdr_model *m,
					   stray_real alpha);

/* eq. R's nodes (z, weight) for this detector: STRAY_DET_RESID_NODES, or
 * one (z 0, weight 1) when it has no background-error term. */
unsigned stray_detector_resid_nodes(const struct stray_detector *d,
				    stray_real z[STRAY_DET_RESID_NODES],
				    stray_real w[STRAY_DET_RESID_NODES]);

#endif /* STRAY_DETECTOR_PIXEL_H */
