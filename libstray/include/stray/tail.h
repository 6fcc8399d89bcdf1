/*
 * tail.h - far-tail probabilities in the log domain (freestanding).
 *
 * The false-detection probability of a star window (thesis eq. 2.17) spans
 * hundreds of decades between the Sun on axis and a well-baffled angle, so
 * every tail here is returned as a natural logarithm: ln Q(z) stays finite
 * and relatively accurate down to Q = 1e-300 and far beyond.  The type is
 * stray_real (config.h): double, or float in flight builds, where ln Q is
 * still finite at z = 40 (ln Q = -804, kept to ~1e-4 absolute).
 */
#ifndef STRAY_TAIL_H
#define STRAY_TAIL_H

#include "stray/error.h"

/* ln Q(z), Q(z) = P(X > z) for a standard normal X (eq. 2.17 kernel). */
stray_real stray_log_gauss_q(stray_real z);

/* Q(z) itself; underflows to 0 only where ln Q(z) < ln of the type's
 * smallest subnormal. */
stray_real stray_gauss_q(stray_real z);

/* z such that Q(z) = p, 0 < p < 1, by bracketed root finding on ln Q. */
int stray_gauss_q_inv(stray_real p, stray_real *z, struct stray_error *err);

/*
 * ln P(a, x): the regularized lower incomplete gamma function, a > 0,
 * x >= 0.  For integer k, P(k, mu) = Pr(N >= k) of a Poisson count N with
 * mean mu, so this is the exact Poisson upper tail; for real a it is the
 * continuous extension used to keep FDR(alpha) smooth and monotone.
 */
int stray_log_gamma_p(stray_real a, stray_real x, stray_real *log_p,
		      struct stray_error *err);

/* ln Q(a, x) = ln(1 - P(a, x)), the complementary tail. */
int stray_log_gamma_q(stray_real a, stray_real x, stray_real *log_q,
		      struct stray_error *err);

/* ln(exp(a) + exp(b)) without overflow or underflow. */
stray_real stray_log_add(stray_real a, stray_real b);

#endif /* STRAY_TAIL_H */
