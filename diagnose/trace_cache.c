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

#include "path_rows.h"
#include "trace_cache.h"
#include "stray/errfmt.h"
#include "tracer/integrator.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

/* The scene's `--set` list for a geometry key (NaN: the scene's own). */
static int geometry_sets(const struct diag_eval *e, const double *geo,
			 char buf[][64], const char **sets)
{
	int n = 0, i;

	for (i = 0; i < e->n_sets; i++)
		sets[n++] = e->sets[i];
	if (!isnan(geo[DIAG_GEO_EDGE_RADIUS])) {
		snprintf(buf[0], 64, "edge_radius=%.9g",
			 geo[DIAG_GEO_EDGE_RADIUS]);
		sets[n++] = buf[0];
	}
	if (!isnan(geo[DIAG_GEO_ACCEPT])) {
		snprintf(buf[1], 64, "accept_half_angle_deg=%.9g",
			 geo[DIAG_GEO_ACCEPT] >= 90.0 ? 0.0 :
			 geo[DIAG_GEO_ACCEPT]);
		sets[n++] = buf[1];
	}
	if (!isnan(geo[DIAG_GEO_BEVEL_UPPER])) {
		snprintf(buf[2], 64, "bevel_face=%s",
			 geo[DIAG_GEO_BEVEL_UPPER] > 0.5 ? "upper" : "lower");
		sets[n++] = buf[2];
	}
	return n;
}

/* Interior groups: the Lambertian (or ABg) coating the causes re-weight. */
static void classify_groups(const struct tracer_scene *s, int *interior,
			    double *rho, double *base_rho)
{
	size_t k;

	*base_rho = NAN;
	for (k = 0; k < TRACER_GROUP_MAX; k++) {
		interior[k] = diag_group_interior(s, k);
		rho[k] = k < s->mesh.n_group ? s->material[k].rho : 0.0;
		if (interior[k] && isnan(*base_rho))
			*base_rho = s->material[k].rho;
	}
}

/* Direct light (order 0) is not in the path table: it does not depend on
 * any reflectance, so it enters as rows with n = 0, summed over batches in
 * the table's units (the same contributions the integrator accumulates). */
static size_t direct_rows(struct diag_trace *t, const struct tracer_result *r,
			  size_t m)
{
	size_t j;

	for (j = 0; j < r->n_theta; j++) {
		if (!diag_direct_row(r, j, &t->v[m], &t->var[m]))
			continue;
		t->j[m] = (unsigned)j;
		t->n_int[m] = 0;
		m++;
	}
	return m;
}

/*
 * The path table reduced to (angle, n interior, v, var) rows, in key
 * order: the rows are summed in this order, and a table merged from a
 * distributed trace (mpi/) holds the same entries in other slots.
 */
static int reduce_paths(struct diag_trace *t, const struct tracer_result *r,
			const struct tracer_scene *s, struct stray_error *err)
{
	const struct tracer_path_table *pt = &r->paths;
	const struct tracer_path_entry **sorted;
	int interior[TRACER_GROUP_MAX], g[TRACER_SEQ_MAX];
	double rho[TRACER_GROUP_MAX], B = r->n_batches;
	size_t i, m = 0, n_used = 0;

	size_t cap = pt->n + r->n_theta;

	classify_groups(s, interior, rho, &t->base_rho);
	t->j = malloc(cap * sizeof(*t->j));
	t->n_int = malloc(cap * sizeof(*t->n_int));
	t->v = malloc(cap * sizeof(*t->v));
	t->var = malloc(cap * sizeof(*t->var));
	sorted = diag_paths_sorted(pt, &n_used);
	if (!t->j || !t->n_int || !t->v || !t->var || !sorted) {
		free(sorted);
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory for the path table");
	}
	for (i = 0; i < n_used; i++) {
		const struct tracer_path_entry *pe = sorted[i];
		int n, k, n_int = 0;
		double ext = 1.0;

		n = tracer_seq_unpack(pe->seq, g);
		for (k = 0; k < n; k++) {
			if (g[k] >= 0 && g[k] < TRACER_GROUP_MAX &&
			    interior[g[k]]) {
				n_int++;
				/* groups coated apart (a vanes file's per-
				 * group materials, a mesh's): rho' scales
				 * them all, their ratios kept; 1 when equal */
				if (t->base_rho > 0.0)
					ext *= rho[g[k]] / t->base_rho;
			}
			else if (g[k] >= 0 && g[k] < TRACER_GROUP_MAX)
				ext *= rho[g[k]];
		}
		t->j[m] = pe->theta_index;
		t->n_int[m] = (unsigned char)n_int;
		t->v[m] = pe->value * ext;
		/* variance of the all-batch sum from the batch sums */
		t->var[m] = diag_batch_var(pe->value, pe->value_b2, B) *
			    ext * ext;
		m++;
	}
	free(sorted);
	m = direct_rows(t, r, m);
	t->n_e = m;
	return STRAY_OK;
}

static void direct_share(struct diag_trace *t, const struct tracer_result *r)
{
	size_t j;

	for (j = 0; j < t->n_theta; j++) {
		double all, d, s;

		tracer_result_power(r, j, -1, &all, &s);
		tracer_result_power(r, j, 0, &d, &s);
		t->direct[j] = all > 0.0 ? d / all : 0.0;
	}
}

/*
 * The relative covariance of alpha(theta_i) between measured angles, from
 * the spread of the batches (delta method, as tracer_result_alpha does
 * for one angle): every angle shares the same detector-side paths, so
 * the simulation errors are correlated and a common-mode error would
 * otherwise pass for a cause (a reflectance off by the model's own noise).
 */
static int batch_covariance(const struct diag_eval *e, struct diag_trace *t,
			    const struct tracer_result *r,
			    struct stray_error *err)
{
	size_t n = e->n, nt = r->n_theta, i, k, j;
	int b, B = r->n_batches, o;
	double *mean = calloc(nt, sizeof(*mean)), *dev;

	t->relcov = calloc(n * n, sizeof(*t->relcov));
	dev = malloc((n + 1) * sizeof(*dev));
	if (!mean || !t->relcov || !dev) {
		free(mean);
		free(dev);
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	}
	for (b = 0; b < B; b++)
		for (j = 0; j < nt; j++)
			for (o = 0; o < TRACER_ORDERS; o++)
				mean[j] += r->power[((size_t)b * nt + j) *
						    TRACER_ORDERS + o] / B;
	for (b = 0; b < B; b++) {
		double ref = 0.0;

		for (o = 0; o < TRACER_ORDERS; o++)
			ref += r->power[((size_t)b * nt + t->ref) *
					TRACER_ORDERS + o];
		ref = mean[t->ref] > 0.0 ? ref / mean[t->ref] : 1.0;
		for (i = 0; i < n; i++) {
			double pj = 0.0;

			j = t->idx[i * DIAG_SUB + DIAG_SUB / 2];
			for (o = 0; o < TRACER_ORDERS; o++)
				pj += r->power[((size_t)b * nt + j) *
					       TRACER_ORDERS + o];
			dev[i] = mean[j] > 0.0 ? pj / mean[j] - ref : 0.0;
		}
		for (i = 0; i < n; i++)
			for (k = 0; k < n; k++)
				t->relcov[i * n + k] += dev[i] * dev[k] /
					((double)B * (B - 1));
	}
	free(mean);
	free(dev);
	return STRAY_OK;
}

int diag_scene_build(const struct diag_eval *e, const double *geo,
		     struct diag_scene *ds, struct stray_error *err)
{
	int n = geometry_sets(e, geo, ds->buf, ds->sets), rc;
	struct tracer_scene_spec spec = { e->scene, ds->sets, n, e->lens,
					  0.0, 0.0 };

	/* the ABg lobe (cause_abg_scatter.c) and the beam axis through the
	 * pivot (cause_pivot_offset.c) are edits after loading: in the spec
	 * too, so that stray-mpi's ranks build this scene */
	if (!isnan(geo[DIAG_GEO_ABG_G]) && geo[DIAG_GEO_ABG_G] > 0.0)
		spec.abg_g = geo[DIAG_GEO_ABG_G];
	if (!isnan(geo[DIAG_GEO_PIVOT]))
		spec.beam_shift_z = geo[DIAG_GEO_PIVOT];
	ds->spec = spec;
	ds->lens.n = 0;
	ds->lens.theta_deg = ds->lens.t = NULL;
	tracer_scene_init(&ds->s);
	rc = tracer_scene_load(e->scene, ds->sets, n, &ds->s, err);
	if (!rc && e->lens)	/* system curve */
		rc = tracer_lens_load(e->lens, &ds->lens, err);
	if (!rc)
		tracer_scene_spec_edit(&ds->spec, &ds->s);
	if (!rc)
		rc = tracer_scene_commit(&ds->s, err);
	return rc;
}

int diag_geometry_check(const struct diag_eval *e, const double *geo,
			struct stray_error *err)
{
	char buf[3][64];
	const char *sets[DIAG_SETS_MAX + 3];
	struct tracer_scene s;
	int n = geometry_sets(e, geo, buf, sets), rc;

	tracer_scene_init(&s);
	rc = tracer_scene_load(e->scene, sets, n, &s, err);
	tracer_scene_free(&s);
	return rc;
}

void diag_scene_free(struct diag_scene *ds)
{
	tracer_scene_free(&ds->s);
	tracer_lens_free(&ds->lens);
}

void diag_trace_opts(const struct diag_eval *e, const struct diag_trace *t,
		     const struct diag_scene *ds, struct tracer_trace_opts *o)
{
	tracer_trace_defaults(o);
	o->theta_deg = t->theta;
	o->n_theta = t->n_theta;
	o->n_paths = t->fine ? (e->n_paths + 3) / 4 : e->n_paths;
	o->seed = e->seed;
	o->threads = e->threads;
	o->record_paths = 1;
	o->lens = e->lens ? &ds->lens : NULL;
}

int diag_trace_fill(struct diag_eval *e, struct diag_trace *t,
		    const struct tracer_result *r, const struct tracer_scene *s,
		    struct stray_error *err)
{
	int rc;

	direct_share(t, r);
	rc = reduce_paths(t, r, s, err);
	if (!rc)
		rc = batch_covariance(e, t, r, err);
	return rc;
}

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
