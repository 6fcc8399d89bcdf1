/*
 * angle.c - visits carried from the stage's read-back angle to the
 * commanded one along the curve's local slope (reduce_angle.h).
 */
#include <math.h>

#include "stray/reduce_angle.h"

double stray_curve_log_slope(const struct stray_curve_point *p, size_t n,
			     size_t k)
{
	size_t a = k > 0 ? k - 1 : k, b = k + 1 < n ? k + 1 : k;

	if (a == b || !(p[a].alpha > 0.0) || !(p[b].alpha > 0.0) ||
	    p[b].theta_deg == p[a].theta_deg)
		return 0.0;
	/* eq. 3.12: alpha ~ exp(g theta) locally */
	return (log(p[b].alpha) - log(p[a].alpha)) /
	       (p[b].theta_deg - p[a].theta_deg);
}

/* The curve point of an angle (points are in increasing theta). */
static size_t point_of(const struct stray_curve_point *p, size_t n,
		       double theta)
{
	size_t k, best = 0;

	for (k = 1; k < n; k++)
		if (fabs(p[k].theta_deg - theta) <
		    fabs(p[best].theta_deg - theta))
			best = k;
	return best;
}

double stray_visits_to_commanded(struct stray_visit *v, size_t n,
				 const double *theta_rb,
				 const struct stray_curve_point *p,
				 size_t n_p)
{
	double worst = 0.0;
	size_t i;

	if (n_p == 0)
		return 0.0;
	for (i = 0; i < n; i++) {
		double d = v[i].theta_deg - theta_rb[i], f;

		/* On axis a lens is symmetric: alpha depends on |theta|,
		 * and the first point's slope is the one-sided one. */
		if (fabs(v[i].theta_deg) <= STRAY_THETA_TOL_DEG)
			d = -fabs(theta_rb[i]);
		if (d == 0.0 || !isfinite(d))
			continue;
		worst = fmax(worst, fabs(d));
		f = exp(stray_curve_log_slope(p, n_p,
				point_of(p, n_p, v[i].theta_deg)) * d);
		v[i].power *= f;
		v[i].var_power *= f * f;
	}
	return worst;
}
