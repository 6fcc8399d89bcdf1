/*
 * curve.c - interpolation of attenuation curves and the exclusion angle
 * (thesis §1, §5.1, fig. 5.1).  Freestanding.
 */
#include <math.h>

#include "stray/config.h"
#include "stray/curve.h"

int stray_curve_check(const struct stray_curve_view *c,
		      struct stray_error *err)
{
	size_t i;

	if (c->n < 1)
		return stray_error_set(err, STRAY_EINVAL, "theta_deg",
			STRAY_MSG("curve has no rows"));
	for (i = 0; i < c->n; i++) {
		if (!isfinite(c->theta_deg[i]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"theta_deg", STRAY_MSG("must be finite"),
				c->theta_deg[i]);
		if (i > 0 && !(c->theta_deg[i] > c->theta_deg[i - 1]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"theta_deg", STRAY_MSG("must be strictly increasing"),
				c->theta_deg[i]);
		if (!(isfinite(c->alpha[i]) && c->alpha[i] >= 0.0))
			return stray_error_set_value(err, STRAY_EINVAL, "alpha",
				STRAY_MSG("must be finite and >= 0"),
				c->alpha[i]);
		if (c->sigma && !(isfinite(c->sigma[i]) && c->sigma[i] >= 0.0))
			return stray_error_set_value(err, STRAY_EINVAL, "sigma",
				STRAY_MSG("must be finite and >= 0"),
				c->sigma[i]);
	}
	return STRAY_OK;
}

/* Log-linear interpolation between (x0, y0) and (x1, y1) at x. */
static double loglin(double x0, double y0, double x1, double y1, double x)
{
	double t = (x - x0) / (x1 - x0);

	if (y0 <= 0.0 || y1 <= 0.0)
		return y0 + t * (y1 - y0);
	return exp(log(y0) + t * (log(y1) - log(y0)));
}

double stray_curve_alpha_at(const struct stray_curve_view *c,
			    double theta_deg)
{
	size_t lo = 0, hi = c->n - 1;

	if (theta_deg <= c->theta_deg[0])
		return c->alpha[0];
	if (theta_deg >= c->theta_deg[hi])
		return c->alpha[hi];
	while (hi - lo > 1) {	/* bisection: at most log2(n) steps */
		size_t mid = lo + (hi - lo) / 2;

		if (c->theta_deg[mid] <= theta_deg)
			lo = mid;
		else
			hi = mid;
	}
	return loglin(c->theta_deg[lo], c->alpha[lo], c->theta_deg[hi],
		      c->alpha[hi], theta_deg);
}

/* alpha_i + k sigma_i, clamped at 0 (k = 0 gives the curve itself). */
static double shifted(const struct stray_curve_view *c, size_t i, double k)
{
	double v = c->alpha[i] + (c->sigma ? k * c->sigma[i] : 0.0);

	return v > 0.0 ? v : 0.0;
}

/*
 * The crossing of alpha_req after the last sample at or above it.  *verdict
 * is 0 when excluded, else the reason: that sample is the last one, or the
 * sample after it lies in or beyond the aperture plane (only the geometric
 * zero there takes the curve below).
 */
static void crossing(const struct stray_curve_view *c, double alpha_req,
		     double k, double *theta_deg, const char **why,
		     double *last_above)
{
	size_t i = c->n;
	double a0, a1, x0, x1, t;

	while (i > 0 && shifted(c, i - 1, k) < alpha_req)
		i--;
	*why = NULL;
	*last_above = i > 0 ? c->theta_deg[i - 1] : (double)NAN;
	if (i == 0) {		/* never at or above: excluded everywhere */
		*theta_deg = c->theta_deg[0];
		return;
	}
	if (i == c->n || !(c->theta_deg[i] < STRAY_APERTURE_PLANE_DEG)) {
		*why = i == c->n ? STRAY_EXCL_ENDS_ABOVE : STRAY_EXCL_PLANE_ONLY;
		*theta_deg = (double)NAN;
		return;
	}
	/* Sample i-1 is at or above alpha_req, sample i below it. */
	a0 = shifted(c, i - 1, k);
	a1 = shifted(c, i, k);
	x0 = c->theta_deg[i - 1];
	x1 = c->theta_deg[i];
	if (a1 > 0.0)
		t = log(alpha_req / a0) / log(a1 / a0);
	else
		t = (alpha_req - a0) / (a1 - a0);
	*theta_deg = x0 + t * (x1 - x0);
}

static int req_check(double alpha_req, struct stray_error *err)
{
	if (!(isfinite(alpha_req) && alpha_req > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "alpha_required",
			STRAY_MSG("must be finite and > 0"), alpha_req);
	return STRAY_OK;
}

int stray_exclusion_angle(const struct stray_curve_view *c, double alpha_req,
			  double *theta_deg, struct stray_error *err)
{
	const char *why;
	double last;
	int rc;

	if ((rc = req_check(alpha_req, err)) != STRAY_OK ||
	    (rc = stray_curve_check(c, err)) != STRAY_OK)
		return rc;
	crossing(c, alpha_req, 0.0, theta_deg, &why, &last);
	if (why)
		return stray_error_set_value(err, STRAY_ERANGE, "theta_deg",
					     STRAY_MSG(why), last);
	return STRAY_OK;
}

int stray_exclusion_interval(const struct stray_curve_view *c,
			     double alpha_req, double k_sigma,
			     struct stray_exclusion *out,
			     struct stray_error *err)
{
	const char *why;
	double last;
	int rc;

	if ((rc = req_check(alpha_req, err)) != STRAY_OK ||
	    (rc = stray_curve_check(c, err)) != STRAY_OK)
		return rc;
	crossing(c, alpha_req, 0.0, &out->theta_deg, &out->reason,
		 &out->last_above_deg);
	out->excluded = out->reason == NULL;
	out->has_interval = c->sigma != 0;
	out->theta_lo_deg = out->theta_hi_deg = out->theta_deg;
	out->hi_reached = out->excluded;
	if (!c->sigma)
		return STRAY_OK;
	crossing(c, alpha_req, -k_sigma, &out->theta_lo_deg, &why, &last);
	crossing(c, alpha_req, k_sigma, &out->theta_hi_deg, &why, &last);
	out->hi_reached = why == NULL;
	return STRAY_OK;
}
