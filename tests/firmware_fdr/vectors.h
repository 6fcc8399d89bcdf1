/*
 * vectors.h - the shared test vectors of firmware_fdr: frames whose
 * expected angles, false stars and flags were computed by ground libstray
 * in double precision (make_vectors.c), run by the host tests and by the
 * emulated Cortex-M4 (target_vectors.c) with the same check.
 */
#ifndef FDRFW_TEST_VECTORS_H
#define FDRFW_TEST_VECTORS_H

#include <stdint.h>

#include "fdrfw/fdrfw.h"

struct fdrfw_vector {
	float q[4];
	float t_exp_s;
	float pos_km[3];
	float sun_dir[3];
	float moon_dir[3];
	double theta_deg[2];	/* Sun, Moon */
	double ln_fdr[2];	/* ln false stars per image, eq. 2.18 */
	uint32_t flags;		/* the FDRFW_VECTOR_FLAGS bits expected */
};

#define FDRFW_VECTOR_FLAGS (FDRFW_SUN_EXCLUDED | FDRFW_MOON_EXCLUDED | \
			    FDRFW_SUN_IN_FOV | FDRFW_MOON_IN_FOV)

/* Agreement asked by issue #6: FDR within 1e-3 relative (|d ln| <=
 * 1e-3), identical flags; angles to 1e-3 deg.  Below 1e-30 false stars
 * per image both must just be below it: relative agreement there would
 * ask float angles to resolve d ln FDR = (z^2/2) d ln alpha with z^2/2 in
 * the hundreds, for a rate that is zero for any purpose. */
#define FDRFW_VECTOR_LN_TOL 1e-3
#define FDRFW_VECTOR_LN_FLOOR (-69.0775527898)	/* ln 1e-30 */
#define FDRFW_VECTOR_THETA_TOL_DEG 1e-3

/* The vector as a frame input (given directions). */
void fdrfw_vector_input(const struct fdrfw_vector *v, struct fdrfw_input *in);

/*
 * 0 when out agrees with v; else 1 + the index of the first field that
 * does not (1-2 theta, 3-4 ln_fdr, 5 flags).  *worst gets the largest
 * |d ln FDR| seen.
 */
int fdrfw_vector_check(const struct fdrfw_vector *v,
		       const struct fdrfw_output *out, double *worst);

#endif /* FDRFW_TEST_VECTORS_H */
