/*
 * path_rows.c - interior groups, the sorted path table and direct-light
 * rows of a trace, for trace_cache.c and surfaces.c.
 */
#include <stdlib.h>

#include "path_rows.h"
#include "tracer/brdf.h"

int diag_group_interior(const struct tracer_scene *s, size_t g)
{
	const struct tracer_brdf *m = &s->material[g];

	return g < s->mesh.n_group && m->ops &&
	       (m->ops == &tracer_brdf_lambert_ops ||
		m->ops == &tracer_brdf_abg_ops);
}

static int cmp_entry(const void *a, const void *b)
{
	const struct tracer_path_entry *x =
		*(const struct tracer_path_entry *const *)a;
	const struct tracer_path_entry *y =
		*(const struct tracer_path_entry *const *)b;

	if (x->theta_index != y->theta_index)
		return x->theta_index < y->theta_index ? -1 : 1;
	return (x->seq > y->seq) - (x->seq < y->seq);
}

const struct tracer_path_entry **diag_paths_sorted(
	const struct tracer_path_table *pt, size_t *n)
{
	const struct tracer_path_entry **sorted;
	size_t i, m = 0;

	sorted = malloc((pt->n + 1) * sizeof(*sorted));
	*n = 0;
	if (!sorted)
		return NULL;
	for (i = 0; i < pt->cap; i++)
		if (pt->e[i].used && m < pt->n)
			sorted[m++] = &pt->e[i];
	qsort(sorted, m, sizeof(*sorted), cmp_entry);
	*n = m;
	return sorted;
}

double diag_batch_var(double sum, double sum2, double B)
{
	double var = B > 1 ? B / (B - 1.0) * (sum2 - sum * sum / B) : 0.0;

	return var > 0.0 ? var : 0.0;
}

int diag_direct_row(const struct tracer_result *r, size_t j, double *v,
		    double *var)
{
	double sum = 0.0, s2 = 0.0;
	int b;

	for (b = 0; b < r->n_batches; b++) {
		double x = r->power[((size_t)b * r->n_theta + j) *
				    TRACER_ORDERS];

		sum += x;
		s2 += x * x;
	}
	if (sum <= 0.0)
		return 0;
	*v = sum;
	*var = diag_batch_var(sum, s2, r->n_batches);
	return 1;
}
