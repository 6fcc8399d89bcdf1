/*
 * source_fdr.h - expected false stars from a point or an extended source,
 * through libstray's FDR core (internal to firmware_fdr).
 */
#ifndef FDRFW_SOURCE_FDR_H
#define FDRFW_SOURCE_FDR_H

#include "fdrfw/earth.h"
#include "fdrfw/fdrfw.h"

/* What one source does to a frame. */
struct fdrfw_source_result {
	double ln_fdr;		/* ln of expected false stars, eq. 2.18 */
	int excluded;		/* FDR at the exclusion envelope >= tolerated */
};

/*
 * A point source of flux f_src at theta_deg off axis.  With latched set,
 * the envelope is read hysteresis_deg nearer the axis, so a raised flag
 * clears only that far past the exclusion angle.
 */
int fdrfw_point_source(const struct fdrfw_ctx *ctx, float t_exp_s,
		       double f_src, float theta_deg, int latched,
		       struct fdrfw_source_result *res);

/* The sunlit Earth over the cap's quadrature, boresight b (unit). */
int fdrfw_earth_source(const struct fdrfw_ctx *ctx, float t_exp_s,
		       const struct fdrfw_earth_cap *cap, const float b[3],
		       int latched, struct fdrfw_source_result *res);

#endif /* FDRFW_SOURCE_FDR_H */
