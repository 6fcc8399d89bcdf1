/*
 * light_alloc.c - how many light-side samples (strategy B) each angle
 * gets, from the pilot's data rather than from angle thresholds (users
 * bring their own baffles).
 *
 * Per angle j the pilot gives, per detector path, alpha_j and the
 * variance v_j of strategy A and v1_j of its single scatter (from its
 * batches), and B's samples e with pA/pB.  With q B samples per detector
 * path the balance heuristic is (at worst: fixed counts do better) one
 * sample of N = nA (1 + q) from the mixture cA pA + cB pB, cA = 1/(1+q),
 * cB = q/(1+q) (Veach 1997, PhD thesis, §9.2.2), whose single-scatter
 * variance per detector path is (E_B[e^2 / (cA pA/pB + cB)] - mu^2)/(1+q).
 * The relative variance at j is then
 *   rel_j(q) = (v_j - v1_j + (M2_j(q) - mu_j^2) / (1 + q)) / alpha_j^2,
 * scored on a grid of q (light.h).  The time to a relative error e at
 * every angle is max_j rel_j (c_a + sum_j q_j c_b_j) / e^2 (c the ray
 * casts per A path and per B sample, counted, not timed: the choice is
 * the same on every machine and thread count).  For a target T each angle
 * takes the least q with rel_j(q) <= T (or its best); the targets tried
 * are the scored rel values, and the least time wins.
 */
#include <math.h>
#include <stdlib.h>

#include "light.h"

#define TARGETS 256	/* targets tried, spread over the scored values */

struct angle_stats {
	double alpha, rest;	/* alpha_j, v_j - v1_j */
	double rel[TRACER_LIGHT_GRID];	/* rel_j at each grid ratio */
	double cb;		/* casts per B sample */
};

static void stats_of(const struct tracer_result *pr, const double *lp,
		     size_t j, struct angle_stats *a)
{
	double m = 0.0, sg = 0.0, m1 = 0.0, sg1 = 0.0, v, v1, mu;
	double st[TRACER_LIGHT_STATS] = { 0.0 };
	int b, k;

	tracer_result_power(pr, j, -1, &m, &sg);
	tracer_result_power(pr, j, 1, &m1, &sg1);
	v = sg * sg * (double)pr->n_paths;
	v1 = sg1 * sg1 * (double)pr->n_paths;
	a->alpha = m;
	a->rest = fmax(v - v1, 0.0);
	for (b = 0; b < pr->n_batches; b++)	/* batch order */
		for (k = 0; k < TRACER_LIGHT_STATS; k++)
			st[k] += lp[((size_t)b * pr->n_theta + j) *
				    TRACER_LIGHT_STATS + k];
	a->cb = st[0] > 0.0 ? st[2] / st[0] : 0.0;
	mu = st[0] > 0.0 ? st[1] / st[0] : 0.0;
	for (k = 0; k < TRACER_LIGHT_GRID; k++) {
		double q = tracer_light_grid_q(k);

		a->rel[k] = m <= 0.0 ? 0.0 : mu <= 0.0 ? v / (m * m) :
			    (a->rest + fmax(st[3 + k] / st[0] - mu * mu, 0.0) /
			     (1.0 + q)) / (m * m);
	}
	if (mu <= 0.0)	/* B sees none of this angle */
		for (k = 1; k < TRACER_LIGHT_GRID; k++)
			a->rel[k] = INFINITY;
}

/* Predicted time (casts x worst relative variance) for target T. */
static double time_for(const struct angle_stats *st, size_t n, double ca,
		       double T, double *q)
{
	double worst = 0.0, cost = ca;
	size_t j;

	for (j = 0; j < n; j++) {
		int k, best = 0;

		/* k = 0 (no B), then the ratios from the least up */
		for (k = 0; k < TRACER_LIGHT_GRID; k++) {
			int g = k == 0 ? 0 : TRACER_LIGHT_GRID - k;

			if (st[j].rel[g] < st[j].rel[best])
				best = g;
			if (st[j].rel[g] <= T) {
				best = g;
				break;
			}
		}
		q[j] = tracer_light_grid_q(best);
		worst = fmax(worst, st[j].rel[best]);
		cost += q[j] * st[j].cb;
	}
	return worst * cost;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

void tracer_light_alloc(const struct tracer_result *pr,
			const double *light_pilot, double *q)
{
	size_t n = pr->n_theta, nt = n * TRACER_LIGHT_GRID, j, k, m = 0;
	struct angle_stats *st = calloc(n, sizeof(*st));
	double *tq = malloc(n * sizeof(double));
	double *targets = malloc(nt * sizeof(double)), best, ca;

	for (j = 0; j < n; j++)
		q[j] = 0.0;
	if (!st || !tq || !targets || pr->n_paths == 0)
		goto out;
	ca = (double)pr->casts / (double)pr->n_paths;
	for (j = 0; j < n; j++) {
		stats_of(pr, light_pilot, j, &st[j]);
		for (k = 0; k < TRACER_LIGHT_GRID; k++)
			if (isfinite(st[j].rel[k]))
				targets[m++] = st[j].rel[k];
	}
	qsort(targets, m, sizeof(double), cmp_double);
	best = time_for(st, n, ca, INFINITY, q);	/* no B */
	for (k = 0; k < TARGETS && m > 0; k++) {
		double t = time_for(st, n, ca, targets[k * m / TARGETS], tq);

		if (t < best) {
			best = t;
			for (j = 0; j < n; j++)
				q[j] = tq[j];
		}
	}
out:
	free(st);
	free(tq);
	free(targets);
}
