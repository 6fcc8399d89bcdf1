/*
 * trace_cache.c - traces of the scene at one geometry, cached by the
 * geometry key, reduced to what re-weighting needs.
 *
 * Every trace uses the same seed (common random numbers): neighbouring
 * nodes of a parameter grid then differ by the geometry, not by noise,
 * so interpolating between them and differencing for the fit's Jacobian
 * stay smooth.  The path table (tracer/paths.h) holds contribution /
 * prod rho per (angle, group sequence); here each entry keeps its number
 * of interior scatters n and the product of the other groups' rho, so
 * the detector power at interior reflectance rho' is
 *   P(theta) = sum v * rho'^n        (thesis §4 re-weighting).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "trace_beams.h"
#include "trace_cache.h"
#include "stray/errfmt.h"
#include "tracer/integrator.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

static int trace_geometry(struct diag_eval *e, struct diag_trace *t,
			  struct stray_error *err)
{
	struct diag_scene ds;
	struct tracer_trace_opts o;
	struct tracer_result r;
	int rc;

	memset(&r, 0, sizeof(r));
	rc = diag_scene_build(e, t->geo, &ds, err);
	if (!rc) {
		diag_trace_opts(e, t, &ds, &o);
		rc = tracer_run(e->runner, &ds.spec, &ds.s, &o, &r, err);
	}
	if (!rc) {
		e->trace_seconds += r.seconds;
		e->n_traces++;
		rc = diag_trace_fill(e, t, &r, &ds.s, err);
	}
	tracer_result_free(&r);
	diag_scene_free(&ds);
	return rc;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

static size_t find_angle(const double *v, size_t n, double x)
{
	size_t lo = 0, hi = n;

	while (hi - lo > 1) {	/* v sorted, x present */
		size_t mid = (lo + hi) / 2;

		if (v[mid] <= x)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

/* The angles of a trace: 0 (the reference) and each measured angle, or
 * with `fine` the DIAG_SUB points theta_i + k step, |k| <= DIAG_SUB / 2 (|.|: the
 * nominal scene is symmetric about the axis). */
static int trace_angles(const struct diag_eval *e, struct diag_trace *t,
			struct stray_error *err)
{
	size_t i, n = 0, per = t->fine ? DIAG_SUB : 1, u;
	double *a = malloc((e->n * per + 1) * sizeof(*a));
	int k;

	t->idx = malloc(e->n * DIAG_SUB * sizeof(*t->idx));
	if (!a || !t->idx) {
		free(a);
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	}
	a[n++] = 0.0;
	for (i = 0; i < e->n; i++)
		for (k = 0; k < (int)per; k++) {
			double d = t->fine ? (k - DIAG_SUB / 2) *
				e->sub_step_deg : 0.0;

			a[n++] = fmin(fabs(e->theta_deg[i] + d), 180.0);
		}
	qsort(a, n, sizeof(*a), cmp_double);
	for (i = 1, u = 1; i < n; i++)
		if (a[i] != a[u - 1])
			a[u++] = a[i];
	t->theta = a;
	t->n_theta = u;
	t->ref = 0;
	for (i = 0; i < e->n; i++)
		for (k = 0; k < DIAG_SUB; k++) {
			double d = t->fine ? (k - DIAG_SUB / 2) *
				e->sub_step_deg : 0.0;

			t->idx[i * DIAG_SUB + k] = find_angle(a, u,
				fmin(fabs(e->theta_deg[i] + d), 180.0));
		}
	return STRAY_OK;
}

static void trace_free(struct diag_trace *t)
{
	if (!t)
		return;
	free(t->theta);
	free(t->idx);
	free(t->direct);
	free(t->relcov);
	free(t->j);
	free(t->n_int);
	free(t->v);
	free(t->var);
	free(t);
}

static int same_key(const double *a, const double *b)
{
	int i;

	for (i = 0; i < DIAG_GEO_N; i++)
		if (!(a[i] == b[i] || (isnan(a[i]) && isnan(b[i]))))
			return 0;
	return 1;
}

static const struct diag_trace *cached(const struct diag_eval *e,
				       const double *geo, int fine)
{
	size_t i;

	for (i = 0; i < e->n_cache; i++)
		if (e->cache[i]->fine == fine && same_key(e->cache[i]->geo, geo))
			return e->cache[i];
	return NULL;
}

static int cache_room(struct diag_eval *e, size_t more,
		      struct stray_error *err)
{
	size_t cap = e->cap_cache ? e->cap_cache : 16;
	struct diag_trace **c;

	while (cap < e->n_cache + more)
		cap *= 2;
	if (cap == e->cap_cache)
		return STRAY_OK;
	c = realloc(e->cache, cap * sizeof(*c));
	if (!c)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	e->cache = c;
	e->cap_cache = cap;
	return STRAY_OK;
}

/* A trace of geometry geo with its angles set, not yet traced. */
static int new_trace(const struct diag_eval *e, const double *geo, int fine,
		     struct diag_trace **out, struct stray_error *err)
{
	struct diag_trace *t = calloc(1, sizeof(*t));
	int rc;

	*out = t;
	if (!t)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	memcpy(t->geo, geo, sizeof(t->geo));
	t->fine = fine;
	rc = trace_angles(e, t, err);
	if (!rc) {
		t->direct = calloc(t->n_theta, sizeof(*t->direct));
		if (!t->direct)
			rc = stray_error_set(err, STRAY_ENOMEM, "diagnose",
					     "out of memory");
	}
	return rc;
}


/*
 * A pivot-offset node: it and every other node of the pivot axis at the
 * same geometry not traced yet, in one pass (trace_beams.c).  The fit
 * of the pivot axis asks for its nodes in turn, so they are all used.
 */
static int trace_pivot_nodes(struct diag_eval *e, const double *geo,
			     struct stray_error *err)
{
	const struct diag_cause *c = diag_eval_axis_cause(e, DIAG_GEO_PIVOT);
	struct diag_trace *ts[DIAG_PIVOT_NODES_MAX + 1];
	double key[DIAG_GEO_N];
	size_t K = 0, k;
	int i, rc = STRAY_OK;

	memcpy(key, geo, sizeof(key));
	for (i = -1; c && i < c->n_nodes && !rc; i++) {
		double v = i < 0 ? geo[DIAG_GEO_PIVOT] : c->nodes[i];

		if (i >= 0 && (v == c->param[0].nominal ||
			       v == geo[DIAG_GEO_PIVOT] ||
			       K > DIAG_PIVOT_NODES_MAX))
			continue;
		key[DIAG_GEO_PIVOT] = v;
		if (cached(e, key, 0))
			continue;
		rc = new_trace(e, key, 0, &ts[K++], err);
	}
	if (!rc)
		rc = cache_room(e, K, err);
	if (!rc)
		rc = diag_trace_beams(e, ts, K, err);
	for (k = 0; k < K; k++) {
		if (rc)
			trace_free(ts[k]);
		else
			e->cache[e->n_cache++] = ts[k];
	}
	return rc;
}

int diag_trace_get(struct diag_eval *e, const double *geo, int fine,
		   const struct diag_trace **out, struct stray_error *err)
{
	struct diag_trace *t = NULL;
	int rc;

	*out = cached(e, geo, fine);
	if (*out)
		return STRAY_OK;
	if (e->no_trace) {	/* candidates.c: the caller's thread traces */
		e->missed = 1;
		return stray_error_set(err, STRAY_ERANGE, "diagnose",
				       "a trace not made yet");
	}
	if (!fine && !isnan(geo[DIAG_GEO_PIVOT])) {
		rc = trace_pivot_nodes(e, geo, err);
		*out = rc ? NULL : cached(e, geo, fine);
		return rc;
	}
	rc = cache_room(e, 1, err);
	if (!rc)
		rc = new_trace(e, geo, fine, &t, err);
	if (!rc)
		rc = trace_geometry(e, t, err);
	if (rc) {
		trace_free(t);
		return rc;
	}
	e->cache[e->n_cache++] = t;
	*out = t;
	return STRAY_OK;
}

int diag_trace_cache_reserve(struct diag_eval *e, size_t more,
			     struct stray_error *err)
{
	return cache_room(e, more, err);
}

void diag_trace_cache_free(struct diag_eval *e)
{
	size_t i;

	for (i = 0; i < e->n_cache; i++)
		trace_free(e->cache[i]);
	free(e->cache);
	e->cache = NULL;
	e->n_cache = e->cap_cache = 0;
}

/* Power and its variance per traced angle at interior reflectance rho. */
void diag_trace_power(const struct diag_trace *t, double rho, double *p,
		      double *var)
{
	double pw[TRACER_SEQ_MAX + 1], pw2[TRACER_SEQ_MAX + 1];
	size_t i;
	int k;

	if (isnan(rho))
		rho = t->base_rho;
	pw[0] = pw2[0] = 1.0;
	for (k = 1; k <= TRACER_SEQ_MAX; k++) {
		pw[k] = pw[k - 1] * rho;
		pw2[k] = pw[k] * pw[k];
	}
	memset(p, 0, t->n_theta * sizeof(*p));
	memset(var, 0, t->n_theta * sizeof(*var));
	for (i = 0; i < t->n_e; i++) {
		p[t->j[i]] += t->v[i] * pw[t->n_int[i]];
		var[t->j[i]] += t->var[i] * pw2[t->n_int[i]];
	}
}
