/*
 * curve.h - attenuation curves alpha(theta) and exclusion angles
 * (thesis §1, §5.1, fig. 5.1).  Freestanding: the curve is a view of
 * caller-owned arrays; loading and saving CSV lives in curve_io.h.
 */
#ifndef STRAY_CURVE_H
#define STRAY_CURVE_H

#include <stddef.h>

#include "stray/error.h"

struct stray_curve_view {
	size_t n;
	const double *theta_deg;	/* strictly increasing */
	const double *alpha;		/* >= 0, normalised to alpha(0) = 1 */
	const double *sigma;		/* one standard error, or NULL */
};

/* Angles finite and strictly increasing, alpha and sigma finite and >= 0. */
int stray_curve_check(const struct stray_curve_view *c,
		      struct stray_error *err);

/*
 * alpha at theta_deg by log-linear interpolation (attenuation falls by
 * decades, so ln alpha is the quantity that is near-linear in theta);
 * linear where an end point is 0; clamped to the end values outside.
 */
double stray_curve_alpha_at(const struct stray_curve_view *c,
			    double theta_deg);

/*
 * The Sun in the aperture plane: a traced curve drops to its geometric zero
 * there (no projected aperture), whatever the baffle does.
 */
#define STRAY_APERTURE_PLANE_DEG 90.0

/*
 * The one exclusion verdict (fig. 5.1) that every command uses: a source is
 * excluded from theta on when the curve, after its last sample at or above
 * alpha_req, falls below alpha_req at a sample *below the aperture plane*
 * (theta < 90 deg); the angle is the log-linear crossing (linear into an
 * exact 0).  When no sample reaches alpha_req, the first angle.  A curve
 * that ends above alpha_req, or reaches it only by dropping to the
 * geometric zero at 90 deg, is not excluded by the baffle: STRAY_ERANGE,
 * with the reason in err (the caller reports it, exit 0).
 */
int stray_exclusion_angle(const struct stray_curve_view *c, double alpha_req,
			  double *theta_deg, struct stray_error *err);

struct stray_exclusion {
	double theta_deg;	/* from the curve itself; NaN: not excluded */
	double theta_lo_deg;	/* from alpha - k sigma (optimistic); NaN: never */
	double theta_hi_deg;	/* from alpha + k sigma (pessimistic) */
	int has_interval;	/* 0 when the curve has no sigma */
	int hi_reached;		/* 0 when alpha + k sigma is never excluded */
	int excluded;		/* 0: not excluded by the baffle (reason) */
	const char *reason;	/* why not (static text), NULL when excluded */
	double last_above_deg;	/* last angle at or above alpha_req, or NaN */
};

/* Why a source is not excluded (the texts of stray_exclusion.reason). */
#define STRAY_EXCL_ENDS_ABOVE \
	"the curve ends above alpha_required at its last angle"
#define STRAY_EXCL_PLANE_ONLY \
	"the curve stays above alpha_required below the aperture plane " \
	"(90 deg): it falls under it only at the geometric zero of the " \
	"plane, not by the baffle"

/*
 * The verdict with its uncertainty: the same rule for the curves
 * alpha -/+ k_sigma * sigma (sigma from the curve) brackets the angle.
 * STRAY_OK whether or not the source is excluded (out->excluded says;
 * out->theta_deg is NaN when not); an error only for bad input.
 */
int stray_exclusion_interval(const struct stray_curve_view *c,
			     double alpha_req, double k_sigma,
			     struct stray_exclusion *out,
			     struct stray_error *err);

#endif /* STRAY_CURVE_H */
