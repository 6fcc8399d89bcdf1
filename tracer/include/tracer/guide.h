/*
 * guide.h - adaptive importance sampling of the detector-side direction.
 *
 * A pilot trace scores each cell of a G x G grid over the direction's two
 * primary-sample coordinates by sqrt(sum_j E[c_j^2 | cell] / P_j^2): the
 * density that minimises the summed relative variance of all angles j of
 * the sweep (Kahn and Marshall 1953, optimal importance density; the
 * square root form for a sum of estimators).  The main trace samples
 * cells from a defensive mixture, half uniform and half that score
 * (Hesterberg 1995, Technometrics 37(2)), so no region is ever starved
 * and every weight stays below 2.  The result stays unbiased whatever the
 * pilot saw.
 */
#ifndef TRACER_GUIDE_H
#define TRACER_GUIDE_H

#include <stddef.h>

#define TRACER_GUIDE_G 32
#define TRACER_GUIDE_CELLS (TRACER_GUIDE_G * TRACER_GUIDE_G)

struct tracer_guide {
	double p[TRACER_GUIDE_CELLS];		/* cell probabilities */
	double row_cdf[TRACER_GUIDE_G + 1];	/* over rows (u2 axis) */
	double col_cdf[TRACER_GUIDE_G][TRACER_GUIDE_G + 1];
};

/* Pilot statistics per cell: sum over paths of c_j^2 (per angle). */
struct tracer_guide_stats {
	size_t n_theta;
	double *s2;		/* [cell][theta] */
};

/* Build from pilot statistics and the pilot's power estimates P_j. */
void tracer_guide_build(struct tracer_guide *g,
			const struct tracer_guide_stats *st, const double *p);

/* Uniform (u1, u2) -> warped (u1, u2) and weight 1 / (G^2 p(cell)). */
double tracer_guide_sample(const struct tracer_guide *g, double *u1,
			   double *u2);

/* The cell of a primary-sample point. */
int tracer_guide_cell(double u1, double u2);

#endif /* TRACER_GUIDE_H */
