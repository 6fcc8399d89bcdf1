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
