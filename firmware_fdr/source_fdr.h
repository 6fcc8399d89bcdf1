/*
 * source_fdr.h - expected false stars from a point or an extended source,
 * through libstray's FDR core (internal to firmware_fdr).
 */
#ifndef FDRFW_SOURCE_FDR_H
#define FDRFW_SOURCE_FDR_H

#include "fdrfw/earth.h"
#include "fdrfw/fdrfw.h"

/*
 * The model in ctx from its (checked) table, z = Q^-1(Pr_drs) solved once,
 * I_sdt at the nominal exposure.  FDRFW_ERANGE if the model is not valid.
 */
int fdrfw_fdr_init(struct fdrfw_ctx *ctx);

/* What one source does to a frame. */
struct fdrfw_source_result {
	stray_real ln_fdr;	/* ln of expected false stars, eq. 2.18 or
				 * the detector's grid */
	stray_real p_drs;	/* the DRS's detection (grid; NaN: thesis) */
	int excluded;		/* FDR at the exclusion envelope >= tolerated,
				 * or (grid) P_drs there below Pr_drs */
	int negligible;		/* the envelope's light changes nothing */
};

/*
 * A point source of flux f_src at theta_deg off axis, at the exposure the
 * context's threshold is for (fdrfw_set_exposure).  With latched set,
 * the envelope is read hysteresis_deg nearer the axis, so a raised flag
 * clears only that far past the exclusion angle.
 */
int fdrfw_point_source(struct fdrfw_ctx *ctx, stray_real f_src,
		       float theta_deg, int latched,
		       struct fdrfw_source_result *res);

/* A detector table's answer (its grid, issue 28) for the light f_src at
 * attenuation alpha, its flag at the envelope's env. */
void fdrfw_grid_source(struct fdrfw_ctx *ctx, stray_real f_src, float alpha,
		       float env, struct fdrfw_source_result *res);

/* No light from a source (eclipsed, the night side). */
void fdrfw_source_none(const struct fdrfw_ctx *ctx,
		       struct fdrfw_source_result *res);

/* The sunlit Earth over the cap's quadrature, boresight b (unit), the
 * cap's nearest point theta_deg off axis (its light is not looked at
 * node by node where even there it would make a rate below 1e-30). */
int fdrfw_earth_source(struct fdrfw_ctx *ctx,
		       const struct fdrfw_earth_cap *cap, const float b[3],
		       float theta_deg, int latched,
		       struct fdrfw_source_result *res);

#endif /* FDRFW_SOURCE_FDR_H */
