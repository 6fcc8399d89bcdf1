/*
 * reduce_angle.h - the stage's read-back angle (ANGLERB) in the curve
 * (beyond the thesis).  A move is accepted within the stage's tolerance,
 * so a visit may be taken a little off its commanded angle; on a steep
 * curve that is a real error (slope x offset), the same in every repeat,
 * which the repeats cannot show.  Each visit's power is carried from the
 * read-back angle to the commanded one along the curve's local
 * logarithmic slope: P(theta_cmd) = P(theta_rb) exp(g (theta_cmd -
 * theta_rb)), g = d ln alpha / d theta (eq. 3.12) from the neighbouring
 * points (central differences; one-sided at the ends).  On axis the
 * offset is -|theta_rb| (a lens is symmetric about its axis).
 */
#ifndef STRAY_REDUCE_ANGLE_H
#define STRAY_REDUCE_ANGLE_H

#include <stddef.h>

#include "stray/reduce_curve.h"

/* d ln alpha / d theta at point k of a curve (0 where alpha <= 0). */
double stray_curve_log_slope(const struct stray_curve_point *p, size_t n,
			     size_t k);

/*
 * Move the power (and its variance) of every visit from its read-back
 * angle theta_rb[i] to its commanded v[i].theta_deg, by the slopes of the
 * curve p (n_p points, from these visits).  Returns the largest
 * |theta_cmd - theta_rb| seen (deg).
 */
double stray_visits_to_commanded(struct stray_visit *v, size_t n,
				 const double *theta_rb,
				 const struct stray_curve_point *p,
				 size_t n_p);

#endif /* STRAY_REDUCE_ANGLE_H */
