/*
 * detector_pixel.c - what every detector model shares at the pixel level
 * (stray/detector_pixel.h): a pixel's variance, a star's light in a
 * pixel, TETRA3's k sigma threshold and the nodes of the background-error
 * term (eq. R of detector.c).  Freestanding C99, no heap.
 */
#include "stray/detector_pixel.h"
#include "stray/tail.h"

stray_real stray_detector_pixel_var(const struct stray_fdr_model *m,
				    stray_real alpha)
{
	return stray_fdr_pixel_photons(m, alpha) +
	       m->read_noise_e * m->read_noise_e +
	       m->dark_current_e_s * m->t_exp_s;
}

/* Fraction of a star's photons in pixel (i, j) from the star, sigma s,
 * the star at (ox, oy) from the centre of pixel (0, 0). */
stray_real stray_detector_psf_pixel(stray_real s, stray_real ox,
				    stray_real oy, int i, int j)
{
	stray_real k = 1 / (s * STRAY_R(1.41421356237309505));
	stray_real gx = STRAY_R(0.5) * (stray_erfc((i - STRAY_R(0.5) - ox) * k) -
				stray_erfc((i + STRAY_R(0.5) - ox) * k));
	stray_real gy = STRAY_R(0.5) * (stray_erfc((j - STRAY_R(0.5) - oy) * k) -
				stray_erfc((j + STRAY_R(0.5) - oy) * k));

	return gx * gy;
}

/* The k sigma threshold of TETRA3: k times the frame's RMS after the
 * background is removed, the root mean square over the map's regions. */
stray_real stray_detector_tetra3_threshold(const struct stray_detector *d,
					   const struct stray_fdr_model *m,
					   stray_real alpha)
{
	/* the map's rel_alpha has mean 1, so the mean variance is that of
	 * the mean level: the variance is linear in I_px */
	return d->sigma_k * stray_sqrt(stray_detector_pixel_var(m, alpha));
}

/* Gauss-Hermite nodes and weights of N(0, 1) for eq. R (detector.c). */
static const stray_real gh_z[STRAY_DET_RESID_NODES] = {
	STRAY_R(0.0), STRAY_R(1.154405394739968), STRAY_R(-1.154405394739968),
	STRAY_R(2.366759410734541), STRAY_R(-2.366759410734541),
	STRAY_R(3.750439717725742), STRAY_R(-3.750439717725742)
};
static const stray_real gh_w[STRAY_DET_RESID_NODES] = {
	STRAY_R(0.457142857142857), STRAY_R(0.240123178605013),
	STRAY_R(0.240123178605013), STRAY_R(0.030757123967586),
	STRAY_R(0.030757123967586), STRAY_R(0.000548268855972),
	STRAY_R(0.000548268855972)
};

unsigned stray_detector_resid_nodes(const struct stray_detector *d,
				    stray_real z[STRAY_DET_RESID_NODES],
				    stray_real w[STRAY_DET_RESID_NODES])
{
	unsigned k;

	if (!(d->bg_resid_rel > 0) || (d->kind != STRAY_DET_WINDOW &&
				       d->kind != STRAY_DET_THRESHOLD)) {
		z[0] = 0;
		w[0] = 1;
		return 1;
	}
	for (k = 0; k < STRAY_DET_RESID_NODES; k++) {
		z[k] = gh_z[k];
		w[k] = gh_w[k];
	}
	return STRAY_DET_RESID_NODES;
}
