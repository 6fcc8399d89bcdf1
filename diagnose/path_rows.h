/*
 * path_rows.h - what the trace cache (trace_cache.c) and the surface
 * diagnosis (surfaces.c) both read off a trace: the interior groups, the
 * path table in key order, and the rows of direct light (private to
 * diagnose/).
 */
#ifndef DIAGNOSE_PATH_ROWS_H
#define DIAGNOSE_PATH_ROWS_H

#include <stddef.h>

#include "tracer/integrator.h"
#include "tracer/scene_load.h"

/* Group g is an interior coating the causes re-weight: Lambertian or
 * ABg. */
int diag_group_interior(const struct tracer_scene *s, size_t g);

/* The used entries of pt sorted by (angle, sequence), so sums do not
 * depend on the hash layout (a table merged by mpi/ holds the same
 * entries in other slots); *n of them.  malloc'd (free it); NULL when
 * out of memory. */
const struct tracer_path_entry **diag_paths_sorted(
	const struct tracer_path_table *pt, size_t *n);

/* Variance of the all-batch sum from the sum and the sum of squares of
 * B batch sums, 0 when negative or B <= 1. */
double diag_batch_var(double sum, double sum2, double B);

/* Direct light (order 0) at angle j summed over the batches, *v, and its
 * variance; 0 when there is none at j (no row), else 1. */
int diag_direct_row(const struct tracer_result *r, size_t j, double *v,
		    double *var);

#endif /* DIAGNOSE_PATH_ROWS_H */
