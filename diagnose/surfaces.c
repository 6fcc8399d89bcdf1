/*
 * surfaces.c - the surface at fault (issue 17 item 4; thesis §4
 * re-weighting, per surface group).
 *
 * One trace of the scene records, per angle and surface-group sequence,
 * sum contribution / prod rho (tracer/paths.h).  A row keeps its base
 * value v = value * prod rho(group) and the candidate groups it visits;
 * with a factor f_g per group (reflectance of a Lambertian group, the A
 * of an ABg group: both multiply the BRDF, so each visit scales the path
 * by f_g) the detector power is
 *   P(theta) = sum_rows v prod_{visits} f_g        (no re-trace)
 * and alpha = P(theta) / P(0).  The fit is of log10 residuals with the
 * measured sigma and the path table's own (batch) variance, diagonal.
 * Few surfaces change (sparsity): greedy forward selection, a group
 * enters when its log10 factor, fitted together with those already in,
 * lowers BIC = chi2 + k ln n by more than DIAG_BIC_MARGIN; at most
 * DIAG_SURF_NAMED_MAX groups.  Intervals: profile chi2 (the others
 * re-fitted), delta chi2 = DIAG_CI_DCHI2 max(1, reduced chi2), as fit.c.
 * The extended model is written as a JSON scene file (tracer/scene_file.c)
 * with its mesh as OBJ, and confirmed by tracing that file.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "diagnose/diag_fit.h"
#include "diagnose/diag_result.h"
#include "diagnose/diag_surfaces.h"
#include "path_rows.h"
#include "surfaces.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/integrator.h"
#include "tracer/obj_export.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"


static int oom(struct stray_error *err)
{
	return stray_error_set(err, STRAY_ENOMEM, "diagnose", "out of memory");
}

/* Rows of the path table (key order, so sums do not depend on the hash
 * layout) and the direct light (order 0, no group) per angle. */
static int build_rows(struct diag_surf_table *t, const struct tracer_result *r,
		      const struct tracer_scene *s, struct stray_error *err)
{
	const struct tracer_path_table *pt = &r->paths;
	const struct tracer_path_entry **sorted;
	int cand_of[TRACER_GROUP_MAX], g[TRACER_SEQ_MAX], k;
	size_t i, m = 0, n_used = 0, cap = pt->n + r->n_theta;
	double B = r->n_batches;

	for (k = 0; k < TRACER_GROUP_MAX; k++)
		cand_of[k] = -1;
	t->j = malloc(cap * sizeof(*t->j));
	t->n_c = malloc(cap * sizeof(*t->n_c));
	t->c = malloc(cap * sizeof(*t->c));
	t->v = malloc(cap * sizeof(*t->v));
	t->var = malloc(cap * sizeof(*t->var));
	sorted = diag_paths_sorted(pt, &n_used);
	if (!t->j || !t->n_c || !t->c || !t->v || !t->var || !sorted) {
		free(sorted);
		return oom(err);
	}
	for (i = 0; i < n_used; i++) {
		const struct tracer_path_entry *pe = sorted[i];
		int n = tracer_seq_unpack(pe->seq, g), nc = 0;
		double prod = 1.0;

		for (k = 0; k < n; k++) {
			if (g[k] < 0 || g[k] >= TRACER_GROUP_MAX)
				continue;
			prod *= s->material[g[k]].rho;
			if (!diag_group_interior(s, (size_t)g[k]))
				continue;
			if (cand_of[g[k]] < 0) {
				int c = t->n_cand++;

				cand_of[g[k]] = c;
				t->group[c] = g[k];
				t->abg[c] = s->material[g[k]].ops ==
					&tracer_brdf_abg_ops;
				t->rho[c] = s->material[g[k]].rho;
				snprintf(t->name[c], sizeof(t->name[c]), "%s",
					 s->mesh.group_name[g[k]]);
			}
			t->c[m][nc++] = (unsigned char)cand_of[g[k]];
		}
		t->j[m] = pe->theta_index;
		t->n_c[m] = (unsigned char)nc;
		t->v[m] = pe->value * prod;
		t->var[m] = diag_batch_var(pe->value, pe->value_b2, B) *
			    prod * prod;
		m++;
	}
	free(sorted);
	for (i = 0; i < r->n_theta; i++) {	/* direct light */
		if (!diag_direct_row(r, i, &t->v[m], &t->var[m]))
			continue;
		t->j[m] = (unsigned)i;
		t->n_c[m] = 0;
		m++;
	}
	t->n_rows = m;
	return STRAY_OK;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* Load e's lens (NULL path: none) into lens; 0 or an error. */
static int load_lens(const struct diag_eval *e, struct tracer_lens *lens,
		     struct stray_error *err)
{
	memset(lens, 0, sizeof(*lens));
	return e->lens ? tracer_lens_load(e->lens, lens, err) : STRAY_OK;
}

/* Trace scene (a name and its sets) at 0 and the measured angles. */
int diag_surf_trace_scene(struct diag_eval *e, const char *scene,
			  const char *const *sets, int n_sets, int record,
			  double *theta, size_t n_theta,
			  struct tracer_result *r, struct tracer_scene *s,
			  struct stray_error *err)
{
	struct tracer_scene_spec spec = { scene, sets, n_sets, e->lens,
					  0.0, 0.0 };
	struct tracer_trace_opts o;
	struct tracer_lens lens;
	int rc = load_lens(e, &lens, err);

	memset(r, 0, sizeof(*r));
	tracer_scene_init(s);
	if (!rc)
		rc = tracer_scene_load(scene, sets, n_sets, s, err);
	if (!rc)
		rc = tracer_scene_commit(s, err);
	if (!rc) {
		tracer_trace_defaults(&o);
		o.theta_deg = theta;
		o.n_theta = n_theta;
		o.n_paths = e->n_paths;
		o.seed = e->seed;
		o.threads = e->threads;
		o.record_paths = record;
		o.lens = e->lens ? &lens : NULL;
		rc = tracer_run(e->runner, &spec, s, &o, r, err);
	}
	tracer_lens_free(&lens);
	return rc;
}

/* 0 and the measured angles, sorted, unique. */
double *diag_surf_angles(const struct diag_eval *e, size_t *n)
{
	double *a = malloc((e->n + 1) * sizeof(*a));
	size_t i, u = 1;

	if (!a)
		return NULL;
	a[0] = 0.0;
	for (i = 0; i < e->n; i++)
		a[i + 1] = fmin(fabs(e->theta_deg[i]), 180.0);
	qsort(a, e->n + 1, sizeof(*a), cmp_double);
	for (i = 1; i < e->n + 1; i++)
		if (a[i] != a[u - 1])
			a[u++] = a[i];
	*n = u;
	return a;
}

int diag_surf_table_trace(struct diag_eval *e, struct diag_surf_table **out,
			  struct stray_error *err)
{
	struct diag_surf_table *t = calloc(1, sizeof(*t));
	struct tracer_scene s;
	struct tracer_result r;
	int rc;

	*out = NULL;
	if (!t)
		return oom(err);
	t->theta = diag_surf_angles(e, &t->n_theta);
	if (!t->theta) {
		free(t);
		return oom(err);
	}
	rc = diag_surf_trace_scene(e, e->scene, e->sets, e->n_sets, 1, t->theta,
			 t->n_theta, &r, &s, err);
	if (!rc) {
		e->trace_seconds += r.seconds;
		e->n_traces++;
		rc = build_rows(t, &r, &s, err);
	}
	tracer_result_free(&r);
	tracer_scene_free(&s);
	if (rc) {
		diag_surf_table_free(t);
		return rc;
	}
	*out = t;
	return STRAY_OK;
}

void diag_surf_table_free(struct diag_surf_table *t)
{
	if (!t)
		return;
	free(t->theta);
	free(t->j);
	free(t->n_c);
	free(t->c);
	free(t->v);
	free(t->var);
	free(t);
}

size_t diag_surf_find_theta(const struct diag_surf_table *t, double th)
{
	size_t lo = 0, hi = t->n_theta;

	th = fmin(fabs(th), 180.0);
	while (hi - lo > 1) {
		size_t mid = (lo + hi) / 2;

		if (t->theta[mid] <= th)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}
