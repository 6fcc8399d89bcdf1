/*
 * test_util.h - what the cmocka tests share.  cmocka 1.1 (Debian 12) has
 * only a float comparison, so doubles get an explicit-tolerance assertion
 * that prints both values.  Include after <cmocka.h>.
 */
#ifndef STRAY_TEST_UTIL_H
#define STRAY_TEST_UTIL_H

#include <math.h>

/* |a - b| <= tol; NaN never passes. */
#define assert_near(a, b, tol) do { \
		double a_ = (a), b_ = (b), t_ = (tol); \
		if (!(fabs(a_ - b_) <= t_)) \
			fail_msg("%s = %.17g, expected %.17g within %.3g", \
				 #a, a_, b_, t_); \
	} while (0)

/* |a / b - 1| <= rel. */
#define assert_rel(a, b, rel) do { \
		double a_ = (a), b_ = (b), r_ = (rel); \
		if (!(fabs(a_ - b_) <= r_ * fabs(b_))) \
			fail_msg("%s = %.17g, expected %.17g within %.3g relative", \
				 #a, a_, b_, r_); \
	} while (0)

#endif /* STRAY_TEST_UTIL_H */
