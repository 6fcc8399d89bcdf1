/*
 * colour.h - catalogue magnitudes to the sensor's passband (issue 24).
 * A catalogue gives Johnson V and B-V; a star tracker counts the
 * photo-electrons of its own passband (QE), which for a red star are
 * more than V says.  The model: the star is a blackbody at the
 * temperature of its B-V (Ballesteros 2012, EPL 97, 34008:
 * T = 4600 K (1/(0.92 (B-V) + 1.7) + 1/(0.92 (B-V) + 0.62))); the
 * factor is its photon flux through the QE over its energy flux through
 * the Bessell V passband (V magnitudes are energy-weighted), divided by
 * the same ratio at B-V = 0, so that a B-V = 0 star of magnitude V gives
 * the F_0 10^(-0.4 V) of eq. 2.2 (F_0 fixed by Vega, B-V = 0).
 * Left out: absorption lines and bands (the Balmer jump of A and B
 * stars, TiO of M stars), interstellar reddening (a reddened star is
 * taken as a cooler one), luminosity class, variability; the Ballesteros
 * relation is fitted to main-sequence stars over 0 < B-V < 1.5 and is
 * used here on -0.4 .. 2.0 (clamped there).  For the built-in silicon QE
 * (qe_mt9p031_approx) the factor is 1.06 at B-V = -0.4, 0.99 at 0.2 - 0.4,
 * 1.09 at 1.0, 1.23 at 1.4 and 1.32 at 1.6.
 */
#ifndef STRAY_COLOUR_H
#define STRAY_COLOUR_H

#include <stddef.h>

#include "stray/catalogue.h"
#include "stray/error.h"
#include "stray/photometry.h"

#define STRAY_COLOUR_BV_MIN (-0.4)
#define STRAY_COLOUR_BV_MAX 2.0
#define STRAY_COLOUR_N 121	/* B-V steps of 0.02 */

struct stray_colour {
	double f[STRAY_COLOUR_N];	/* factor at B-V_MIN + 0.02 k */
};

/* The blackbody temperature [K] of a B-V (Ballesteros 2012), B-V
 * clamped to [BV_MIN, BV_MAX]. */
double stray_bv_temperature(double b_v);

/* The factor table for the sensor's QE and the V passband. */
int stray_colour_init(struct stray_colour *c, const struct stray_spectrum *qe,
		      const struct stray_spectrum *v_band,
		      struct stray_error *err);

/* The table for sensor QE source qe ("builtin:NAME" or a path) and the
 * built-in Bessell V passband. */
int stray_colour_for_qe(struct stray_colour *c, const char *qe,
			struct stray_error *err);

/* The factor at b_v (linear in the table; clamped at its ends). */
double stray_colour_factor(const struct stray_colour *c, double b_v);

/* Each star's colour from its b_v. */
void stray_colour_apply(const struct stray_colour *c,
			struct stray_cat_star *s, size_t n);

#endif /* STRAY_COLOUR_H */
