/*
 * root.h - bracketed scalar root finding (freestanding).
 *
 * Brent's method (R. P. Brent, Algorithms for Minimization without
 * Derivatives, 1973, ch. 4): inverse quadratic interpolation with bisection
 * as the safeguard, so it keeps the bracket and always converges for a
 * continuous function that changes sign; the iteration count is bounded.
 */
#ifndef STRAY_ROOT_H
#define STRAY_ROOT_H

#include "stray/error.h"

/* f(x) in *y; a non-zero status aborts the search and is returned. */
typedef int (*stray_root_fn)(double x, void *ctx, double *y);

struct stray_root_result {
	double x;		/* the root */
	int iterations;		/* function evaluations used */
};

/*
 * Find x in [lo, hi] with f(x) = 0 to an absolute tolerance xtol.  f(lo)
 * and f(hi) must differ in sign (or one be zero): STRAY_ERANGE otherwise.
 */
int stray_root_brent(stray_root_fn f, void *ctx, double lo, double hi,
		     double xtol, struct stray_root_result *res,
		     struct stray_error *err);

#endif /* STRAY_ROOT_H */
