/*
 * root.c - Brent's bracketed root finder (freestanding).
 *
 * After R. P. Brent, Algorithms for Minimization without Derivatives
 * (Prentice-Hall 1973), ch. 4, procedure zero: keep a sign-changing bracket
 * [b, c], try inverse quadratic (or secant) interpolation, and fall back to
 * bisection whenever the step would not shrink the bracket fast enough.
 */
#include <float.h>
#include <math.h>

#include "stray/config.h"
#include "stray/root.h"

static int same_sign(double u, double v)
{
	return (u > 0.0) == (v > 0.0);
}

/* One interpolation step d, or bisection (d = e = m) when it is unsafe. */
static void brent_step(double a, double b, double c, double fa, double fb,
		       double fc, double m, double tol, double *d, double *e)
{
	double p, q, r, s = fb / fa;

	if (a == c) {		/* secant */
		p = 2.0 * m * s;
		q = 1.0 - s;
	} else {		/* inverse quadratic interpolation */
		q = fa / fc;
		r = fb / fc;
		p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0));
		q = (q - 1.0) * (r - 1.0) * (s - 1.0);
	}
	if (p > 0.0)
		q = -q;
	else
		p = -p;
	if (2.0 * p < 3.0 * m * q - fabs(tol * q) && p < fabs(0.5 * *e * q)) {
		*e = *d;
		*d = p / q;
	} else {
		*d = m;
		*e = m;
	}
}

int stray_root_brent(stray_root_fn f, void *ctx, double lo, double hi,
		     double xtol, struct stray_root_result *res,
		     struct stray_error *err)
{
	double a = lo, b = hi, c, fa, fb, fc, d, e;
	int rc, it;

	if (!(lo < hi) || !isfinite(lo) || !isfinite(hi))
		return stray_error_set(err, STRAY_EINVAL, "bracket",
			STRAY_MSG("needs finite lo < hi"));
	if ((rc = f(a, ctx, &fa)) != STRAY_OK || (rc = f(b, ctx, &fb)) != STRAY_OK)
		return rc;
	if (isnan(fa) || isnan(fb))
		return stray_error_set(err, STRAY_EINVAL, "bracket",
			STRAY_MSG("function is NaN at an end"));
	res->iterations = 2;
	if (fa == 0.0 || fb == 0.0) {
		res->x = fa == 0.0 ? a : b;
		return STRAY_OK;
	}
	if (same_sign(fa, fb))
		return stray_error_set_value(err, STRAY_ERANGE, "bracket",
			STRAY_MSG("function has the same sign at both ends"),
			lo);
	c = a;
	fc = fa;
	d = e = b - a;
	for (it = 0; it < STRAY_ROOT_ITER_MAX; it++) {
		double tol, m;

		if (fabs(fc) < fabs(fb)) {	/* b is the best estimate */
			a = b; b = c; c = a;
			fa = fb; fb = fc; fc = fa;
		}
		tol = 2.0 * DBL_EPSILON * fabs(b) + 0.5 * xtol;
		m = 0.5 * (c - b);
		if (fabs(m) <= tol || fb == 0.0) {
			res->x = b;
			return STRAY_OK;
		}
		if (fabs(e) < tol || fabs(fa) <= fabs(fb))
			d = e = m;
		else
			brent_step(a, b, c, fa, fb, fc, m, tol, &d, &e);
		a = b;
		fa = fb;
		b += fabs(d) > tol ? d : (m > 0.0 ? tol : -tol);
		if ((rc = f(b, ctx, &fb)) != STRAY_OK)
			return rc;
		res->iterations++;
		if (same_sign(fb, fc)) {
			c = a;
			fc = fa;
			d = e = b - a;
		}
	}
	return stray_error_set_value(err, STRAY_ENOCONV, "root",
		STRAY_MSG("Brent iteration limit reached"), b);
}
