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
 * The exclusion angle (fig. 5.1): the smallest theta beyond which the curve
 * stays below alpha_req, found from the last sample at or above alpha_req
 * and the log-linear crossing after it.  When no sample reaches alpha_req,
 * the first angle.  STRAY_ERANGE when the last sample is still at or above
 * alpha_req (the curve ends before the source is excluded).
 */
int stray_exclusion_angle(const struct stray_curve_view *c, double alpha_req,
			  double *theta_deg, struct stray_error *err);

struct stray_exclusion {
	double theta_deg;	/* from the curve itself */
	double theta_lo_deg;	/* from alpha - k sigma (optimistic) */
	double theta_hi_deg;	/* from alpha + k sigma (pessimistic) */
	int has_interval;	/* 0 when the curve has no sigma */
	int hi_reached;		/* 0 when alpha + k sigma never falls below */
};

/*
 * The exclusion angle with its uncertainty: the same crossing for the
 * curves alpha -/+ k_sigma * sigma (sigma from the curve) brackets it.
 */
int stray_exclusion_interval(const struct stray_curve_view *c,
			     double alpha_req, double k_sigma,
			     struct stray_exclusion *out,
			     struct stray_error *err);

#endif /* STRAY_CURVE_H */
