/*
 * reduce_curve.h - from the total power of each angle to the lens curve
 * (thesis §3.2): alpha_lens = P(theta) / P(0) (eq. 3.12), the noise floor
 * sigma_alpha = sigma(theta) / Pbar(0) (eq. 3.13-3.15) and one standard
 * error per point, with source drift tracked by the on-axis revisits.
 *
 * Source drift (beyond the thesis): every visit carries its place in the
 * acquisition order.  With two or more on-axis visits, P(0) is fitted as a
 * straight line in that order (weighted least squares) and each angle is
 * normalised by the line at its own place, which removes a linear drift;
 * the slope's significance says whether drift was seen.
 */
#ifndef STRAY_REDUCE_CURVE_H
#define STRAY_REDUCE_CURVE_H

#include <stddef.h>

#include "stray/error.h"

/* One visit of the gimbal to an angle: the sums of its J image. */
struct stray_visit {
	double theta_deg;
	double order;		/* acquisition order: mean time of its frames
				 * (s after the sweep's first) when every
				 * frame has one, else its mean manifest row */
	double power;		/* eq. 3.9 */
	double var_power;
	double sigma;		/* eq. 3.14 */
	size_t n_pix;		/* n_ppi */
};

struct stray_drift {
	size_t n_ref;		/* on-axis visits */
	int fitted;		/* 1 when n_ref >= 2 */
	int detected;		/* |z| > STRAY_DRIFT_Z */
	double rel_change;	/* slope * order span / P(0) at the first */
	double z;		/* slope / its standard error */
	double p0;		/* P(0) at the first on-axis visit */
	double p0_rel_sigma;	/* relative standard error of P(0), shared
				 * by every alpha (their correlation) */
};

#define STRAY_DRIFT_Z 3.0
/* Angles closer than this are one angle (deg). */
#define STRAY_THETA_TOL_DEG 1e-6

struct stray_curve_point {
	double theta_deg;
	double alpha;		/* eq. 3.12 */
	double sigma;		/* standard error of alpha */
	double noise_floor;	/* eq. 3.15 */
	size_t n_visits;
};

/*
 * Curve points in increasing theta into out (capacity n; *n_out set);
 * visits at one angle are combined by inverse-variance weights.
 * STRAY_ENOTFOUND ("ANGLE") without an on-axis visit; STRAY_EINVAL when
 * P(0) is not positive.
 */
int stray_reduce_curve(const struct stray_visit *v, size_t n,
		       struct stray_curve_point *out, size_t *n_out,
		       struct stray_drift *drift, struct stray_error *err);

#endif /* STRAY_REDUCE_CURVE_H */
