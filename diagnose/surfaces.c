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
#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/integrator.h"
#include "tracer/obj_export.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

struct diag_surf_table {
	size_t n_theta, n_rows;
	double *theta;		/* traced angles, [0] = 0 */
	unsigned *j;		/* row -> traced angle */
	unsigned char *n_c;	/* row -> visits of candidate groups */
	unsigned char (*c)[TRACER_SEQ_MAX];
	double *v, *var;
	int n_cand;
	int group[DIAG_SURF_MAX], abg[DIAG_SURF_MAX];
	double rho[DIAG_SURF_MAX];
	char name[DIAG_SURF_MAX][32];
};

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
static int trace_scene(struct diag_eval *e, const char *scene,
		       const char *const *sets, int n_sets, int record,
		       double *theta, size_t n_theta, struct tracer_result *r,
		       struct tracer_scene *s, struct stray_error *err)
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
static double *angles(const struct diag_eval *e, size_t *n)
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
	t->theta = angles(e, &t->n_theta);
	if (!t->theta) {
		free(t);
		return oom(err);
	}
	rc = trace_scene(e, e->scene, e->sets, e->n_sets, 1, t->theta,
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

/* ---- the re-weighting fit ---- */

struct sfit {
	const struct diag_surf_table *t;
	const struct diag_data *d;
	size_t *jm;		/* measured point -> traced angle */
	size_t n_fit;		/* points with theta != 0 */
	size_t *pt;		/* fitted point -> measured index */
	double *p, *var;	/* per traced angle */
	int n_free, free_c[DIAG_SURF_NAMED_MAX];	/* groups fitted */
	double f[DIAG_SURF_MAX];	/* current factors, 1 = scene */
	const double *base;	/* per measured point, the registry's model
				 * over the nominal (NULL: 1) */
	int fixed_k;		/* profile: this free index fixed, -1 none */
	double fixed_x;
	size_t evals;
};

static void reweight(struct sfit *x)
{
	const struct diag_surf_table *t = x->t;
	size_t i;
	int k;

	memset(x->p, 0, t->n_theta * sizeof(*x->p));
	memset(x->var, 0, t->n_theta * sizeof(*x->var));
	for (i = 0; i < t->n_rows; i++) {
		double w = 1.0;

		for (k = 0; k < t->n_c[i]; k++)
			w *= x->f[t->c[i][k]];
		x->p[t->j[i]] += t->v[i] * w;
		x->var[t->j[i]] += t->var[i] * w * w;
	}
	x->evals++;
}

/* Whitened log10 residuals at the current factors. */
static void residuals(struct sfit *x, double *r)
{
	const struct diag_data *d = x->d;
	double p0 = x->p[0], v0 = p0 > 0.0 ? x->var[0] / (p0 * p0) : 0.0;
	size_t m;

	for (m = 0; m < x->n_fit; m++) {
		size_t i = x->pt[m], j = x->jm[i];
		double a = p0 > 0.0 ? x->p[j] / p0 : 0.0, rm, rs, s;

		a *= x->base ? x->base[i] : 1.0;
		a = a > 1e-30 ? a : 1e-30;
		rm = d->sigma[i] / d->alpha[i];
		rs = x->p[j] > 0.0 ? x->var[j] / (x->p[j] * x->p[j]) + v0 : 0.0;
		s = sqrt(rm * rm + rs) / M_LN10;
		r[m] = log10(d->alpha[i] / a) / s;
	}
}

static int resid_fn(void *user, const double *p, double *r,
		    struct stray_error *err)
{
	struct sfit *x = user;
	int k, q = 0;

	(void)err;
	for (k = 0; k < x->n_free; k++)
		x->f[x->free_c[k]] = pow(10.0, k == x->fixed_k ? x->fixed_x :
					 p[q++]);
	reweight(x);
	residuals(x, r);
	return STRAY_OK;
}

static double hi_bound(const struct diag_surf_table *t, int c)
{
	/* a Lambertian group cannot reflect more than all */
	double h = t->abg[c] || !(t->rho[c] > 0.0) ? DIAG_SURF_LOG_BOUND :
		fmin(DIAG_SURF_LOG_BOUND, log10(1.0 / t->rho[c]));

	return h;
}

/* Fit the free groups' log10 factors (p in/out, all free ones, the
 * fixed one, if any, held at fixed_x); chi2 out. */
static int fit_free(struct sfit *x, double *p, double *chi2, double *r,
		    struct stray_error *err)
{
	double q[DIAG_SURF_NAMED_MAX], lo[DIAG_SURF_NAMED_MAX],
	       hi[DIAG_SURF_NAMED_MAX];
	int k, n = 0, rc;

	for (k = 0; k < x->n_free; k++) {
		if (k == x->fixed_k)
			continue;
		q[n] = p[k];
		lo[n] = -DIAG_SURF_LOG_BOUND;
		hi[n] = hi_bound(x->t, x->free_c[k]);
		n++;
	}
	if (n == 0) {
		resid_fn(x, q, r, err);
		for (*chi2 = 0.0, k = 0; k < (int)x->n_fit; k++)
			*chi2 += r[k] * r[k];
		return STRAY_OK;
	}
	rc = diag_lm(resid_fn, x, n, x->n_fit, q, lo, hi, chi2, err);
	for (n = 0, k = 0; k < x->n_free; k++)
		if (k != x->fixed_k)
			p[k] = q[n++];
	return rc;
}

/* Profile-chi2 edge of free parameter k from best toward bound. */
static int profile_edge(struct sfit *x, const double *best, int k,
			double chi2_min, double target, double bound,
			double *edge, double *r, struct stray_error *err)
{
	double p[DIAG_SURF_NAMED_MAX], in = best[k], out = bound, c;
	double step = bound > best[k] ? 0.02 : -0.02;
	int i, rc = STRAY_OK;

	x->fixed_k = k;
	memcpy(p, best, sizeof(p));
	/* walk out until chi2 exceeds the target, then bisect */
	for (x->fixed_x = best[k] + step;
	     (step > 0 ? x->fixed_x < bound : x->fixed_x > bound) && !rc;
	     x->fixed_x += step, step *= 1.6) {
		rc = fit_free(x, p, &c, r, err);
		if (c - chi2_min >= target) {
			out = x->fixed_x;
			break;
		}
		in = x->fixed_x;
	}
	if (step > 0 ? x->fixed_x >= bound : x->fixed_x <= bound)
		out = bound;
	for (i = 0; i < 30 && !rc && fabs(out - in) > 1e-4; i++) {
		x->fixed_x = 0.5 * (in + out);
		memcpy(p, best, sizeof(p));
		rc = fit_free(x, p, &c, r, err);
		if (c - chi2_min >= target)
			out = x->fixed_x;
		else
			in = x->fixed_x;
	}
	x->fixed_k = -1;
	*edge = 0.5 * (in + out);
	return rc;
}

static double rms_of(const struct sfit *x, const double *r)
{
	/* rms of the plain log10 residuals (not whitened) */
	const struct diag_data *d = x->d;
	double p0 = x->p[0], s = 0.0;
	size_t m;

	(void)r;
	for (m = 0; m < x->n_fit; m++) {
		size_t i = x->pt[m];
		double a = (p0 > 0.0 ? x->p[x->jm[i]] / p0 : 0.0) *
			   (x->base ? x->base[i] : 1.0);
		double l = log10(d->alpha[i] / (a > 1e-30 ? a : 1e-30));

		s += l * l;
	}
	return x->n_fit ? sqrt(s / x->n_fit) : 0.0;
}

static size_t find_theta(const struct diag_surf_table *t, double th)
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

int diag_surfaces_fit(const struct diag_surf_table *t,
		      const struct diag_data *d, struct diag_surfaces *s,
		      struct stray_error *err)
{
	return diag_surfaces_fit_on(t, d, NULL, s, err);
}

int diag_surfaces_fit_on(const struct diag_surf_table *t,
			 const struct diag_data *d, const double *base,
			 struct diag_surfaces *s, struct stray_error *err)
{
	struct sfit x;
	double *r, best[DIAG_SURF_NAMED_MAX] = { 0 }, chi2, ln_n;
	struct timespec t0, t1;
	size_t i;
	int k, c, rc = STRAY_OK;

	clock_gettime(CLOCK_MONOTONIC, &t0);
	memset(s, 0, sizeof(*s));
	memset(&x, 0, sizeof(x));
	s->chi2_retrace = s->rms_retrace = NAN;
	s->n_cand = t->n_cand;
	s->n_rows = t->n_rows;
	for (c = 0; c < t->n_cand; c++) {
		snprintf(s->name[c], sizeof(s->name[c]), "%s", t->name[c]);
		s->group[c] = t->group[c];
		s->abg[c] = t->abg[c];
		s->rho[c] = t->rho[c];
	}
	x.t = t;
	x.d = d;
	x.base = base;
	s->base = base;
	x.fixed_k = -1;
	x.jm = malloc(d->n * sizeof(*x.jm));
	x.pt = malloc(d->n * sizeof(*x.pt));
	x.p = malloc(2 * t->n_theta * sizeof(*x.p));
	r = malloc((d->n + 1) * sizeof(*r));
	if (!x.jm || !x.pt || !x.p || !r) {
		rc = oom(err);
		goto out;
	}
	x.var = x.p + t->n_theta;
	for (c = 0; c < DIAG_SURF_MAX; c++)
		x.f[c] = 1.0;
	for (i = 0; i < d->n; i++) {
		x.jm[i] = find_theta(t, d->theta_deg[i]);
		if (d->theta_deg[i] != 0.0)
			x.pt[x.n_fit++] = i;
	}
	s->n_fit = (int)x.n_fit;
	ln_n = log((double)(x.n_fit > 1 ? x.n_fit : 2));
	fit_free(&x, best, &chi2, r, err);
	s->chi2_before = s->chi2_after = chi2;
	s->bic_before = s->bic_after = chi2;
	s->rms_before = s->rms_after = rms_of(&x, r);
	/* greedy forward selection: the group whose factor, fitted with the
	 * ones already in, lowers BIC the most, while by > the margin */
	while (!rc && x.n_free < DIAG_SURF_NAMED_MAX) {
		double bc = INFINITY, bp[DIAG_SURF_NAMED_MAX];
		int bcand = -1;

		for (c = 0; c < t->n_cand && !rc; c++) {
			double p[DIAG_SURF_NAMED_MAX], c2;
			int in = 0;

			for (k = 0; k < x.n_free; k++)
				in |= x.free_c[k] == c;
			if (in)
				continue;
			memcpy(p, best, sizeof(p));
			p[x.n_free] = 0.0;
			x.free_c[x.n_free++] = c;
			rc = fit_free(&x, p, &c2, r, err);
			x.f[c] = 1.0;
			x.n_free--;
			if (!rc && c2 < bc) {
				bc = c2;
				bcand = c;
				memcpy(bp, p, sizeof(bp));
			}
		}
		if (rc || bcand < 0 || bc + (x.n_free + 1) * ln_n >
		    s->bic_after - DIAG_BIC_MARGIN)
			break;
		x.free_c[x.n_free++] = bcand;
		memcpy(best, bp, sizeof(best));
		s->chi2_after = bc;
		s->bic_after = bc + x.n_free * ln_n;
	}
	/* the final fit and its rms */
	if (!rc)
		rc = fit_free(&x, best, &chi2, r, err);
	if (!rc && x.n_free > 0) {
		int dof = (int)x.n_fit - x.n_free;
		double red = dof > 0 ? chi2 / dof : 1.0;
		double target = DIAG_CI_DCHI2 * (red > 1.0 ? red : 1.0);

		s->chi2_after = chi2;
		s->rms_after = rms_of(&x, r);
		s->n_named = x.n_free;
		for (k = 0; k < x.n_free && !rc; k++) {
			s->named[k] = x.free_c[k];
			s->log10_f[k] = best[k];
			rc = profile_edge(&x, best, k, chi2, target,
					  -DIAG_SURF_LOG_BOUND, &s->ci_lo[k],
					  r, err);
			if (!rc)
				rc = profile_edge(&x, best, k, chi2, target,
						  hi_bound(t, x.free_c[k]),
						  &s->ci_hi[k], r, err);
		}
	}
out:
	s->n_evals = x.evals;
	clock_gettime(CLOCK_MONOTONIC, &t1);
	s->fit_seconds = (double)(t1.tv_sec - t0.tv_sec) +
			 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
	free(x.jm);
	free(x.pt);
	free(x.p);
	free(r);
	return rc;
}

/* ---- the extended model as a scene file ---- */

static double factor_of(const struct diag_surfaces *s, int group)
{
	int k;

	for (k = 0; k < s->n_named; k++)
		if (s->group[s->named[k]] == group)
			return pow(10.0, s->log10_f[k]);
	return 1.0;
}

static void write_vec(FILE *f, const char *key, struct vec3 v)
{
	fprintf(f, "\"%s\": [%.17g, %.17g, %.17g]", key, v.x, v.y, v.z);
}

static void write_material(FILE *f, const struct tracer_brdf *m, double fac)
{
	if (!m->ops)
		fprintf(f, "{ \"type\": \"absorber\" }");
	else if (m->ops == &tracer_brdf_mirror_ops)
		fprintf(f, "{ \"type\": \"mirror\", \"reflectance\": %.17g }",
			m->rho);
	else if (m->ops == &tracer_brdf_abg_ops)
		fprintf(f, "{ \"type\": \"abg\", \"reflectance\": %.17g, "
			"\"a\": %.17g, \"b\": %.17g, \"g\": %.17g }",
			m->rho, m->abg.a * fac, m->abg.b, m->abg.g);
	else
		fprintf(f, "{ \"type\": \"lambert\", \"reflectance\": %.17g }",
			fmin(m->rho * fac, 1.0));
}

/* The mesh as OBJ, written in place (the confirmation's private copy;
 * the user's copy goes through tracer_obj_export, with the run's other
 * outputs). */
static int obj_in_place(const struct tracer_mesh *m, const char *path,
			struct stray_error *err)
{
	FILE *f = fopen(path, "w");
	size_t i, g;

	if (!f)
		return stray_error_set(err, STRAY_EIO, "diagnose",
				       "cannot write the model's mesh");
	for (i = 0; i < m->n_vert; i++)
		fprintf(f, "v %.9g %.9g %.9g\n", m->vert[3 * i],
			m->vert[3 * i + 1], m->vert[3 * i + 2]);
	for (g = 0; g < m->n_group; g++) {
		fprintf(f, "g %s\n", m->group_name[g]);
		for (i = 0; i < m->n_tri; i++)
			if (m->group[i] == g)
				fprintf(f, "f %u %u %u\n", m->tri[3 * i] + 1,
					m->tri[3 * i + 1] + 1,
					m->tri[3 * i + 2] + 1);
	}
	return fclose(f) == 0 ? STRAY_OK :
		stray_error_set(err, STRAY_EIO, "diagnose",
				"cannot write the model's mesh");
}

static void write_scene_json(FILE *f, const struct diag_eval *e,
			     const struct diag_surfaces *s,
			     const struct tracer_scene *sc, const char *obj)
{
	const struct tracer_detector *d = &sc->det;
	size_t g;

	fprintf(f, "{\n  \"comment\": \"stray diagnose --write-model: "
		"%s with %d surface group(s) changed\",\n", e->scene,
		s->n_named);
	fprintf(f, "  \"meshes\": [ { \"file\": \"%s\" } ],\n", obj);
	fprintf(f, "  \"materials\": {\n");
	for (g = 0; g < sc->mesh.n_group; g++) {
		fprintf(f, "    \"%s\": ", sc->mesh.group_name[g]);
		write_material(f, &sc->material[g], factor_of(s, (int)g));
		fprintf(f, "%s\n", g + 1 < sc->mesh.n_group ? "," : "");
	}
	fprintf(f, "  },\n  \"detector\": { \"shape\": \"%s\", ",
		d->shape == TRACER_DET_RECT ? "rect" : "disk");
	write_vec(f, "center", d->center);
	fprintf(f, ", ");
	write_vec(f, "normal", d->normal);
	if (d->shape == TRACER_DET_RECT)
		fprintf(f, ", \"width_mm\": %.17g, \"height_mm\": %.17g",
			2.0 * d->half_w_mm, 2.0 * d->half_h_mm);
	else
		fprintf(f, ", \"radius_mm\": %.17g", d->radius_mm);
	if (d->accept_half_angle_deg > 0.0)
		fprintf(f, ", \"accept_half_angle_deg\": %.17g",
			d->accept_half_angle_deg);
	fprintf(f, " },\n  \"beam\": { ");
	write_vec(f, "center", sc->beam.center);
	fprintf(f, ", ");
	write_vec(f, "normal", sc->beam.normal);
	fprintf(f, ", \"radius_mm\": %.17g }\n}\n", sc->beam.radius_mm);
}

/* in_place: plain stdio (readable at once); else the atomic writer
 * (renamed into place with the run's other outputs). */
static int write_model(const struct diag_eval *e,
		       const struct diag_surfaces *s, const char *path,
		       int in_place, struct stray_error *err)
{
	struct tracer_scene sc;
	struct stray_file_out out;
	char obj[4096];
	const char *base, *dot;
	size_t len = strlen(path);
	FILE *f = NULL;
	int rc;

	dot = strrchr(path, '.');
	if (!dot || strchr(dot, '/'))
		dot = path + len;
	if ((size_t)(dot - path) + 5 > sizeof(obj))
		return stray_error_set(err, STRAY_EINVAL, "--write-model",
				       "path too long");
	snprintf(obj, sizeof(obj), "%.*s.obj", (int)(dot - path), path);
	base = strrchr(obj, '/');
	base = base ? base + 1 : obj;
	tracer_scene_init(&sc);
	rc = tracer_scene_load(e->scene, e->sets, e->n_sets, &sc, err);
	if (!rc)
		rc = in_place ? obj_in_place(&sc.mesh, obj, err) :
			tracer_obj_export(&sc.mesh, obj, err);
	if (!rc && in_place && !(f = fopen(path, "w")))
		rc = stray_error_set(err, STRAY_EIO, "--write-model",
				     "cannot open for writing");
	if (!rc && !in_place) {
		rc = stray_file_open_atomic(&out, path, err);
		f = out.f;
	}
	if (!rc) {
		write_scene_json(f, e, s, &sc, base);
		if (in_place)
			rc = fclose(f) == 0 ? STRAY_OK :
				stray_error_set(err, STRAY_EIO,
						"--write-model", "write failed");
		else
			rc = stray_file_commit(&out, err);
	}
	tracer_scene_free(&sc);
	return rc;
}

int diag_surfaces_write_model(const struct diag_eval *e,
			      const struct diag_surfaces *s, const char *path,
			      struct stray_error *err)
{
	return write_model(e, s, path, 0, err);
}

int diag_surfaces_confirm(struct diag_eval *e, const struct diag_data *d,
			  struct diag_surfaces *s, struct stray_error *err)
{
	char dir[] = "/tmp/stray_model_XXXXXX", model_path[64], obj[64];
	struct diag_surf_table t;
	struct tracer_scene sc;
	struct tracer_result r;
	double chi2 = 0.0, rs = 0.0, a0, s0;
	size_t i, m = 0;
	int rc;

	memset(&t, 0, sizeof(t));
	memset(&r, 0, sizeof(r));
	tracer_scene_init(&sc);
	if (!mkdtemp(dir))
		return stray_error_set(err, STRAY_EIO, "diagnose",
				       "no temporary directory for the model");
	snprintf(model_path, sizeof(model_path), "%s/model.json", dir);
	snprintf(obj, sizeof(obj), "%s/model.obj", dir);
	t.theta = angles(e, &t.n_theta);
	rc = t.theta ? write_model(e, s, model_path, 1, err) : oom(err);
	if (!rc)
		rc = trace_scene(e, model_path, NULL, 0, 0, t.theta, t.n_theta, &r,
			 &sc, err);
	if (!rc) {
		e->trace_seconds += r.seconds;
		e->n_traces++;
		tracer_result_alpha(&r, 0, 0, -1, &a0, &s0);
		for (i = 0; i < d->n; i++) {
			double a, sa, l, sr;

			if (d->theta_deg[i] == 0.0)
				continue;
			tracer_result_alpha(&r, find_theta(&t, d->theta_deg[i]),
					    0, -1, &a, &sa);
			a *= s->base ? s->base[i] : 1.0;
			a = a > 1e-30 ? a : 1e-30;
			l = log10(d->alpha[i] / a);
			sr = sqrt(pow(d->sigma[i] / d->alpha[i], 2) +
				  pow(sa / a, 2)) / M_LN10;
			chi2 += (l / sr) * (l / sr);
			rs += l * l;
			m++;
		}
		s->chi2_retrace = chi2;
		s->rms_retrace = m ? sqrt(rs / m) : 0.0;
	}
	tracer_result_free(&r);
	tracer_scene_free(&sc);
	free(t.theta);
	unlink(model_path);
	unlink(obj);
	rmdir(dir);
	return rc;
}
