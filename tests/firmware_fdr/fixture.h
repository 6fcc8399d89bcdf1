/*
 * fixture.h - a reference attenuation curve and the flight table built
 * from it, shared by the firmware_fdr tests.
 */
#ifndef FDRFW_TEST_FIXTURE_H
#define FDRFW_TEST_FIXTURE_H

#include "fdrfw/table.h"
#include "stray/curve.h"
#include "stray/photometry_io.h"

/* |a - b| <= tol for doubles (this cmocka has only assert_float_equal);
 * include after <cmocka.h> and <math.h>. */
#define assert_near(a, b, tol) do { \
	double a_ = (a), b_ = (b), t_ = (tol); \
	if (!(fabs(a_ - b_) <= t_)) \
		fail_msg("%s = %.10g, expected %.10g +- %.3g", #a, a_, b_, t_); \
} while (0)

/*
 * A ref4-like system curve, 0-85 deg every 1 deg: flat in the field,
 * falling by decades beyond it, with a rise between 46 and 56 deg (lit
 * bevels, ref4-baffle.md) so its exclusion envelope differs from it.
 */
const struct stray_curve_view *fixture_curve(void);

/* The st16-like sensor's reference fluxes (libstray photometry). */
const struct stray_fluxes *fixture_fluxes(void);

/* The table `stray firmware-table` would build from the curve. */
void fixture_table(struct fdrfw_table *t);

#endif /* FDRFW_TEST_FIXTURE_H */
