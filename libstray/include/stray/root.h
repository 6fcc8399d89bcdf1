/*
 * root.h - bracketed scalar root finding (freestanding).
 *
 * Brent's method (R. P. Brent, Algorithms for Minimization without
 * Derivatives, 1973, ch. 4): inverse quadratic interpolation with bisection
 * as the safeguard, so it keeps the bracket and always converges for a
 * continuous function that changes sign; the iteration count is bounded.
 * Works in stray_real (config.h); xtol is absolute, so a float build passes
 * a tolerance scaled to its epsilon (STRAY_TOL).
 */
#ifndef STRAY_ROOT_H
#define STRAY_ROOT_H

#include "stray/error.h"

/* f(x) in *y; a non-zero status aborts the search and is returned. */
typedef int (*stray_root_fn)(stray_real x, void *ctx, stray_real *y);

struct stray_root_result {
	stray_real x;		/* the root */
	int iterations;		/* function evaluations used */
};

/*
 * Find x in [lo, hi] with f(x) = 0 to an absolute tolerance xtol.  f(lo)
 * and f(hi) must differ in sign (or one be zero): STRAY_ERANGE otherwise.
 */
int stray_root_brent(stray_root_fn f, void *ctx, stray_real lo,
		     stray_real hi, stray_real xtol,
		     struct stray_root_result *res,
		     struct stray_error *err);

#endif /* STRAY_ROOT_H */
