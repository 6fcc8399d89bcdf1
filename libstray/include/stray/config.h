/*
 * config.h - build options of the libstray core, in one place.
 *
 * The core (tail, root, fdr, curve, photometry) is freestanding C99: no heap,
 * no stdio, no mutable globals; it needs only <math.h>, which every embedded
 * C library (newlib, picolibc) provides.  Options, each built in CI:
 *
 *   STRAY_NO_ERRMSG   compile the static error texts out (flight builds keep
 *                     the codes only, as nanopb's PB_NO_ERRMSG does).
 *   STRAY_WITH_POISSON=0
 *                     leave the exact-Poisson FDR model out (flight builds
 *                     use the thesis's Gaussian model; this drops lgamma
 *                     and the incomplete-gamma fractions from the image).
 *   STRAY_REAL_FLOAT  compute the FDR core (tail, root, fdr, error values)
 *                     in single precision: flight builds for an FPU that
 *                     has only float (Cortex-M4F).  The host stays double.
 *
 * The core's .c files carry no #ifdef for these: the real type, its
 * constants and its math functions are chosen here, once.
 */
#ifndef STRAY_CONFIG_H
#define STRAY_CONFIG_H

/* Static assert with a C99 fallback (a negative array size fails to build). */
#if defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L
#define STRAY_STATIC_ASSERT(cond, msg) _Static_assert(cond, #msg)
#else
#define STRAY_STATIC_ASSERT_CAT2(a, b) a##b
#define STRAY_STATIC_ASSERT_CAT(a, b) STRAY_STATIC_ASSERT_CAT2(a, b)
#define STRAY_STATIC_ASSERT(cond, msg) \
	typedef char STRAY_STATIC_ASSERT_CAT(stray_static_assert_, \
					     __LINE__)[(cond) ? 1 : -1]
#endif

/*
 * stray_real: the core's floating type.  STRAY_R(c) gives a constant of that
 * type (a cast, folded at compile time, so float builds never promote to
 * double); STRAY_TOL(d) scales a tolerance chosen for double by
 * FLT_EPSILON / DBL_EPSILON = 2^29, and is d itself in double.
 */
#include <float.h>
#include <math.h>

#ifdef STRAY_REAL_FLOAT
typedef float stray_real;
#define STRAY_TOL(d) ((float)((d) * 536870912.0))
#define STRAY_EPSILON FLT_EPSILON
#define STRAY_REAL_MIN FLT_MIN
#define STRAY_REAL_MAX FLT_MAX
#define STRAY_HUGE HUGE_VALF
/* Q(5) = 2.9e-7: erfcf still far from underflow (Q(13) ~ FLT_MIN), and
 * Laplace's fraction at depth 64 already exact to double there. */
#define STRAY_GAUSS_CF_FROM_Z 5.0f
#define stray_exp(x) expf(x)
#define stray_log(x) logf(x)
#define stray_log1p(x) log1pf(x)
#define stray_erfc(x) erfcf(x)
#define stray_lgamma(x) lgammaf(x)
#define stray_sqrt(x) sqrtf(x)
#define stray_fabs(x) fabsf(x)
#else
typedef double stray_real;
#define STRAY_TOL(d) (d)
#define STRAY_EPSILON DBL_EPSILON
#define STRAY_REAL_MIN DBL_MIN
#define STRAY_REAL_MAX DBL_MAX
#define STRAY_HUGE HUGE_VAL
/* Q(26) ~ 1e-149: erfc far from underflow. */
#define STRAY_GAUSS_CF_FROM_Z 26.0
#define stray_exp(x) exp(x)
#define stray_log(x) log(x)
#define stray_log1p(x) log1p(x)
#define stray_erfc(x) erfc(x)
#define stray_lgamma(x) lgamma(x)
#define stray_sqrt(x) sqrt(x)
#define stray_fabs(x) fabs(x)
#endif
#define STRAY_R(c) ((stray_real)(c))

#ifdef STRAY_NO_ERRMSG
#define STRAY_MSG(text) ((const char *)0)
#else
#define STRAY_MSG(text) (text)
#endif

/* 1: the exact-Poisson noise model is built in (the default). */
#ifndef STRAY_WITH_POISSON
#define STRAY_WITH_POISSON 1
#endif

/* Upper bound on the regions of a non-uniform stray-light map (fdr.h). */
#define STRAY_MAP_REGIONS_MAX 64

/* Iteration caps: every loop in the core is bounded by one of these. */
#define STRAY_ROOT_ITER_MAX 200
#define STRAY_SERIES_ITER_MAX 100000

#endif /* STRAY_CONFIG_H */
