/*
 * root.c - Brent's bracketed root finder (freestanding).
 *
 * After R. P. Brent, Algorithms for Minimization without Derivatives
 * (Prentice-Hall 1973), ch. 4, procedure zero: keep a sign-changing bracket
 * [b, c], try inverse quadratic (or secant) interpolation, and fall back to
 * bisection whenever the step would not shrink the bracket fast enough.
 */
#include "stray/config.h"
#include "stray/root.h"

static int same_sign(stray_real u, stray_real v)
{
	return (u > 0) == (v > 0);
}

/* One interpolation step d, or bisection (d = e = m) when it is unsafe. */
static void brent_step(stray_real a, stray_real b, stray_real c,
		       stray_real fa, stray_real fb, stray_real fc,
		       stray_real m, stray_real tol, stray_real *d,
		       stray_real *e)
{
	stray_real p, q, r, s = fb / fa;

	if (a == c) {		/* secant */
		p = 2 * m * s;
		q = 1 - s;
	} else {		/* inverse quadratic interpolation */
		q = fa / fc;
		r = fb / fc;
		p = s * (2 * m * q * (q - r) - (b - a) * (r - 1));
		q = (q - 1) * (r - 1) * (s - 1);
	}
	if (p > 0)
		q = -q;
	else
		p = -p;
	if (2 * p < 3 * m * q - stray_fabs(tol * q) &&
	    p < stray_fabs(STRAY_R(0.5) * *e * q)) {
		*e = *d;
		*d = p / q;
	} else {
		*d = m;
		*e = m;
	}
}

int stray_root_brent(stray_root_fn f, void *ctx, stray_real lo,
		     stray_real hi, stray_real xtol,
		     struct stray_root_result *res, struct stray_error *err)
{
	stray_real a = lo, b = hi, c, fa, fb, fc, d, e;
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
	if (fa == 0 || fb == 0) {
		res->x = fa == 0 ? a : b;
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
		stray_real tol, m;

		/* b is the best estimate */
		if (stray_fabs(fc) < stray_fabs(fb)) {
			a = b; b = c; c = a;
			fa = fb; fb = fc; fc = fa;
		}
		tol = 2 * STRAY_EPSILON * stray_fabs(b) + STRAY_R(0.5) * xtol;
		m = STRAY_R(0.5) * (c - b);
		if (stray_fabs(m) <= tol || fb == 0) {
			res->x = b;
			return STRAY_OK;
		}
		if (stray_fabs(e) < tol || stray_fabs(fa) <= stray_fabs(fb))
			d = e = m;
		else
			brent_step(a, b, c, fa, fb, fc, m, tol, &d, &e);
		a = b;
		fa = fb;
		b += stray_fabs(d) > tol ? d : (m > 0 ? tol : -tol);
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
