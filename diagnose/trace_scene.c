/*
 * trace_scene.c - one trace of the cache (trace_scene.h): the scene built
 * at a geometry key, the options of its trace, and the trace reduced to
 * what re-weighting needs (direct share, path rows with their interior
 * scatters, the batches' covariance).  trace_cache.c keeps the traces by
 * key; trace_beams.c traces the pivot-offset nodes of one geometry in one
 * pass; both build and fill through here.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path_rows.h"
#include "trace_scene.h"
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
