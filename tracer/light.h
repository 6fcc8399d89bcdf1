/*
 * light.h - private to the tracer: strategy B, light-side single scatter
 * (issue 27).  For angle j a point a is sampled uniformly on the beam's
 * aperture disk, the ray from it against the beam's direction finds the
 * directly lit point x, and a uniform detector point p is connected to x
 * (inside the acceptance cone, x the first hit from p).  Its density in
 * dA_p dA_x is pB = (1/A_det)(1/A_ap)|d.n_x|/|d.n_ap|; the detector-side
 * path (strategy A) that makes the same single-scatter path has
 * pA = (1/A_det) pdf_dir(w) cos_x / r^2, pdf_dir = cos_p / (proj g(w)).
 * Both are combined by the balance heuristic (Veach 1997, PhD thesis,
 * Stanford, ch. 9): weights nB pB / (nA pA + nB pB) and nA pA / (...), nA, nB
 * the samples of a batch.  Paths of two and more scatters stay A's.
 */
#ifndef TRACER_LIGHT_H
#define TRACER_LIGHT_H

#include "tracer/batches.h"
#include "worker.h"

/* B samples per batch and angle in the pilot pass (its statistics size
 * the main pass's B: tracer_light_alloc). */
#define TRACER_LIGHT_PILOT 64
/* The ratios the pilot scores (B samples per detector path): 0 and
 * TRACER_LIGHT_RATIO_MAX / 2^k, k < TRACER_LIGHT_GRID - 1. */
#define TRACER_LIGHT_GRID 16
#define TRACER_LIGHT_RATIO_MAX 4.0
/* Pilot statistics per batch and angle: samples, sum of estimates, ray
 * casts, then per grid ratio q the sum of e^2 / (cA pA/pB + cB), cA =
 * 1/(1+q), cB = q/(1+q): the second moment of the balance heuristic's
 * mixture (light_alloc.c). */
#if TRACER_LIGHT_STATS != 3 + TRACER_LIGHT_GRID
#error "batches.h's TRACER_LIGHT_STATS is 3 + TRACER_LIGHT_GRID"
#endif

/* Grid ratio k. */
double tracer_light_grid_q(int k);

/* B samples of an angle with ratio q in a batch of n_a detector paths. */
uint64_t tracer_light_count(double q, uint64_t n_a);

/*
 * pB / pA of a single-scatter path at angle j: f_a = proj g r^2 /
 * (cos_p cos_x) is the detector side's part (proj the cone's projected
 * solid angle, g the guide weight of the path's direction, r the
 * distance from the detector point to x), cos_d = d_j . n_x.
 */
double tracer_light_pdf_ratio(const struct worker_ctx *w, size_t j,
			      double cos_d, double f_a);

/* Strategy A's weight of a single-scatter connection at angle j in a
 * batch of n_a paths (1 where B does not run). */
double tracer_light_weight_a(const struct worker_ctx *w, size_t j,
			     uint64_t n_a, double cos_d, double f_a);

/* Per-batch outputs of B (the batch's rows of the result). */
struct light_out {
	double *acc;		/* [theta][order] */
	double *map;		/* irradiance map, or NULL */
	double *focal;		/* focal sums, or NULL */
	struct tracer_path_table *table;	/* or NULL */
	uint64_t casts, connections;
	int failed;
};

/* B's samples of batch b (n_a detector paths) at every angle with a
 * ratio, tallied with their weights; in the pilot pass, B alone into
 * w->light_pilot. */
void tracer_light_batch(struct worker_ctx *w, int b, uint64_t n_a,
			struct light_out *out);

/* tracer_light_alloc (batches.h): the main pass's B ratio per angle from
 * the pilot's result and B statistics (light_alloc.c). */

#endif /* TRACER_LIGHT_H */
