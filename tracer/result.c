/*
 * result.c - what a trace returns: means and standard errors of detector
 * power from the independent batches, alpha with the delta method.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tracer/integrator.h"

void tracer_result_free(struct tracer_result *res)
{
	free(res->batch_paths);
	free(res->power);
	free(res->energy);
	free(res->theta_deg);
	free(res->dump);
	free(res->dump_len);
	free(res->map);
	free(res->focal);
	free(res->focal_batch);
	tracer_paths_free(&res->paths);
	memset(res, 0, sizeof(*res));
}

/* Per-batch mean of P/(E A_det) at angle j (order < 0: all orders). */
static double batch_mean(const struct tracer_result *r, int b, size_t j,
			 int order)
{
	const double *p = r->power +
			  ((size_t)b * r->n_theta + j) * TRACER_ORDERS;
	double sum = 0.0;
	int k;

	if (order >= 0)
		sum = p[order];
	else
		for (k = 0; k < TRACER_ORDERS; k++)
			sum += p[k];
	return sum / (double)r->batch_paths[b];
}

void tracer_result_power(const struct tracer_result *res, size_t j,
			 int order, double *mean, double *sigma)
{
	double m = 0.0, v = 0.0;
	int b, nb = res->n_batches;

	for (b = 0; b < nb; b++)
		m += batch_mean(res, b, j, order);
	m /= nb;
	for (b = 0; b < nb; b++) {
		double d = batch_mean(res, b, j, order) - m;

		v += d * d;
	}
	*mean = m;
	*sigma = sqrt(v / (nb - 1) / nb);
}

void tracer_result_alpha(const struct tracer_result *res, size_t j,
			 size_t ref, int order, double *alpha, double *sigma)
{
	double pj, pr, s, v = 0.0;
	int b, nb = res->n_batches;

	tracer_result_power(res, j, order, &pj, &s);
	tracer_result_power(res, ref, -1, &pr, &s);
	if (!(pr > 0.0)) {
		*alpha = *sigma = 0.0;
		return;
	}
	*alpha = pj / pr;
	for (b = 0; b < nb; b++) {
		double d = batch_mean(res, b, j, order) -
			   *alpha * batch_mean(res, b, ref, -1);

		v += d * d;
	}
	*sigma = sqrt(v / (nb - 1) / nb) / pr;
}
