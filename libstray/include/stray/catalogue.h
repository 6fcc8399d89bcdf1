/*
 * catalogue.h - the synthetic star catalogue (issue 18): fixed sky
 * positions (RA, Dec) and magnitudes, so that frames rendered through an
 * attitude and the analysis that plate-solves them see the same stars.
 * No real catalogue is installed (docs/frames.md), so this one is
 * procedural: the sky is cut into cells 1 deg high in Dec and about
 * 1 deg wide in RA; each cell holds a Poisson number of stars (uniform
 * in solid angle) with the all-sky counts N(<m) of
 * stray_star_counts_per_deg2, drawn from a splitmix64 stream seeded by
 * (catalogue seed, cell), complete to m = 10.5 (fainter asks are cut
 * there).  The same seed is the same sky, whatever cone
 * is asked for.  Every output that uses it says "synthetic".
 * Hosted layer, no heap, no stdio.
 */
#ifndef STRAY_CATALOGUE_H
#define STRAY_CATALOGUE_H

#include <stddef.h>
#include <stdint.h>

#include "stray/frames.h"

#define STRAY_CATALOGUE_SEED 2014u	/* the toolkit's sky */
#define STRAY_CATALOGUE_MAG_MIN (-1.5)

struct stray_cat_star {
	double ra_deg, dec_deg, mag;
	double u[3];		/* unit vector, inertial (EME2000) */
	double b_v;		/* B-V (0 in the synthetic sky) */
	double colour;		/* photo-e- over those of a B-V = 0 star of
				 * the same mag in the sensor's band (1 in
				 * the synthetic sky; stray/colour.h) */
};

/*
 * Every catalogue star brighter than mag_max within radius_deg of the
 * unit vector dir.  Writes at most max; *n gets the number written;
 * returns the number found (more than max: the buffer was short).
 */
size_t stray_catalogue_cone(uint64_t seed, const double dir[3],
			    double radius_deg, double mag_max,
			    struct stray_cat_star *out, size_t max,
			    size_t *n);

/* An ideal (gnomonic) camera: boresight +z of the head frame, image
 * columns along +x, rows along +y, f_px focal length in pixels, the
 * optical axis at pixel (cx, cy) of the rendered frame. */
struct stray_camera {
	double m_ih[3][3];	/* v_head = m_ih v_inertial */
	double f_px, cx, cy;
};

/* Project one inertial unit vector; 0 when behind the camera. */
int stray_camera_project(const struct stray_camera *c, const double u[3],
			 double *x, double *y);

/*
 * Project the catalogue stars onto a cols x rows frame (margin px beyond
 * the edges kept), as rendered stars with photons f0_e 10^(-0.4 m)
 * times the star's colour factor (eq. 2.2, 2.12).  Returns the number written (at most max).
 */
size_t stray_camera_stars(const struct stray_camera *c,
			  const struct stray_cat_star *cat, size_t n_cat,
			  int cols, int rows, double margin, double f0_e,
			  struct stray_star *out, size_t max);

#endif /* STRAY_CATALOGUE_H */
