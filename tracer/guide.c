/*
 * guide.c - a piecewise-constant 2D density over primary-sample space,
 * sampled by inversion (marginal over rows, then the row's columns).
 */
#include <math.h>

#include "tracer/guide.h"

#define G TRACER_GUIDE_G

int tracer_guide_cell(double u1, double u2)
{
	int c = (int)(u1 * G), r = (int)(u2 * G);

	c = c < 0 ? 0 : c >= G ? G - 1 : c;
	r = r < 0 ? 0 : r >= G ? G - 1 : r;
	return r * G + c;
}

static double cell_score(const struct tracer_guide_stats *st, int cell,
			 const double *p)
{
	double sum = 0.0;
	size_t j;

	for (j = 0; j < st->n_theta; j++)
		if (p[j] > 0.0)
			sum += st->s2[(size_t)cell * st->n_theta + j] /
			       (p[j] * p[j]);
	return sqrt(sum);
}

void tracer_guide_build(struct tracer_guide *g,
			const struct tracer_guide_stats *st, const double *p)
{
	double total = 0.0;
	int i, r, c;

	for (i = 0; i < G * G; i++) {
		g->p[i] = cell_score(st, i, p);
		total += g->p[i];
	}
	/* defensive mixture: half uniform, half the pilot's score */
	for (i = 0; i < G * G; i++)
		g->p[i] = 0.5 / (G * G) +
			  (total > 0.0 ? 0.5 * g->p[i] / total : 0.5 / (G * G));
	g->row_cdf[0] = 0.0;
	for (r = 0; r < G; r++) {
		double row = 0.0;

		for (c = 0; c < G; c++)
			row += g->p[r * G + c];
		g->col_cdf[r][0] = 0.0;
		for (c = 0; c < G; c++)
			g->col_cdf[r][c + 1] = g->col_cdf[r][c] +
					       g->p[r * G + c] / row;
		g->col_cdf[r][G] = 1.0;
		g->row_cdf[r + 1] = g->row_cdf[r] + row;
	}
	g->row_cdf[G] = 1.0;
}

/* Index k with cdf[k] <= u < cdf[k+1], and u rescaled into [0, 1). */
static int invert(const double *cdf, double *u)
{
	int lo = 0, hi = G;
	double w;

	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;

		if (cdf[mid] <= *u)
			lo = mid;
		else
			hi = mid;
	}
	w = cdf[lo + 1] - cdf[lo];
	*u = w > 0.0 ? (*u - cdf[lo]) / w : 0.5;
	if (*u >= 1.0)
		*u = nextafter(1.0, 0.0);
	return lo;
}

double tracer_guide_sample(const struct tracer_guide *g, double *u1,
			   double *u2)
{
	int r = invert(g->row_cdf, u2);
	int c = invert(g->col_cdf[r], u1);

	*u1 = (c + *u1) / G;
	*u2 = (r + *u2) / G;
	return 1.0 / (G * G * g->p[r * G + c]);
}
