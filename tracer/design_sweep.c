/*
 * design_sweep.c - `stray sweep`'s work as one call (design_sweep.h):
 * every design of the grid (the Cartesian product of its axes over the
 * scene's --set parameters) traced, or its kept curve taken back from the
 * state folder when the same run traced it before, and judged: its Sun
 * exclusion angle with the interval from alpha -/+ sigma (thesis §5.1)
 * and alpha at the chosen angles.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/angles.h"
#include "tracer/design_sweep.h"
#include "tracer/scene_load.h"

/* The traced angles, with 0 first (alpha is normalised to P(0)). */
/* A scene parameter from a --grid axis is refused by the scene loader as
 * a --set; name the option the user gave. */
static void blame_grid(const struct design_sweep *a, struct stray_error *err)
{
	int k;

	if (!err || !err->field || strcmp(err->field, "--set") != 0)
		return;
	for (k = 0; k < a->grid.n_axes; k++)
		if (strcmp(err->text, a->grid.axis[k].key) == 0)
			err->field = "--grid";
}

static int make_angles(struct design_sweep *a, double **theta, size_t *n,
		       struct stray_error *err)
{
	double *at = NULL;
	size_t n_at = 0, i;
	const char *list = a->angles ? a->angles : "0:30:5,30:90:1";
	int added, rc = tracer_angles_parse(list, theta, n, err);

	if (!rc) {
		rc = tracer_angles_parse(a->at_list ? a->at_list : "20,30,40",
					 &at, &n_at, err);
		if (rc && err)		/* the parser speaks of --angles */
			err->field = "--alpha-at";
	}
	if (!rc && n_at > SWEEP_AT_MAX)
		rc = stray_error_set_value(err, STRAY_EINVAL, "--alpha-at",
					   "at most 16 angles", (double)n_at);
	for (i = 0; !rc && i < n_at; i++)
		a->at[i] = at[i];
	a->n_at = (int)n_at;
	free(at);
	return rc ? rc : tracer_angles_with_zero(theta, n, &added, err);
}

/* What must match for a kept curve to stand for this run's design. */
static void run_key(const struct design_sweep *a, const char *label,
		    char *buf, size_t size)
{
	int n = snprintf(buf, size, "%s | scene %s | rays %llu seed %llu "
			 "batches %d | angles %s | lens %s", label, a->scene,
			 (unsigned long long)a->o.n_paths,
			 (unsigned long long)a->o.seed, a->o.n_batches,
			 a->angles ? a->angles : "default",
			 a->lens ? a->lens : "none");

	/* a key longer than buf is cut there, the same each run */
	if (n < 0 || (size_t)n >= size)
		buf[size - 1] = '\0';
}

/* A kept curve with this key, or 0 (absent, other run, unreadable). */
static int resume(const char *path, const char *key, struct stray_curve *c)
{
	struct stray_error err;
	char want[1200];
	size_t i;

	if (access(path, F_OK) != 0)
		return 0;
	stray_error_clear(&err);
	if (stray_curve_load(path, c, &err)) {
		stray_file_forget_input(path);	/* broken: traced anew */
		return 0;
	}
	snprintf(want, sizeof(want), " sweep_run: %s", key);
	for (i = 0; i < c->n_meta; i++)
		if (strcmp(c->meta[i], want) == 0)
			return 1;
	stray_curve_free(c);
	stray_file_forget_input(path);	/* another run's: traced anew */
	return 0;
}

/* A design's trace finished: keep its curve (alpha, sigma from theta > 0)
 * in path with the run key, and read it back into c. */
static int keep_curve(const struct design_sweep *a,
		      const struct tracer_result *r, const char *key,
		      const char *path, struct stray_curve *c,
		      struct stray_error *err)
{
	size_t j, n = a->o.n_theta - 1;
	int rc;

	{	/* alpha = P(theta) / P(0): refuse 0/0 (a blocked beam) */
		double p0, s0;

		tracer_result_power(r, 0, -1, &p0, &s0);
		if (!(p0 > 0.0)) {
			stray_error_at(err, STRAY_EINVAL, a->scene, 0, "beam",
				"no on-axis power reaches the detector in this "
				"design (is the beam blocked?): alpha would be 0/0");
			stray_error_text(err, key);
			return STRAY_EINVAL;
		}
	}
	rc = stray_curve_alloc(c, n, 1, err);
	for (j = 0; !rc && j < n; j++) {
		c->theta_deg[j] = a->o.theta_deg[j + 1];
		tracer_result_alpha(r, j + 1, 0, -1, &c->alpha[j],
				    &c->sigma[j]);
	}
	if (!rc)
		rc = stray_curve_add_meta(c, "kind", "baffle", err);
	if (!rc)
		rc = stray_curve_add_meta(c, "sweep_run", key, err);
	if (!rc)
		rc = stray_curve_save(path, c, err);
	stray_curve_free(c);
	/* judged as read back, so a resumed sweep gives the same bytes */
	return rc ? rc : stray_curve_load(path, c, err);
}

/* Sun exclusion angle and alpha at the chosen angles of one curve. */
static int judge(const struct design_sweep *a, const struct stray_curve *c,
		 double alpha_req, struct design_result *d,
		 struct stray_error *err)
{
	struct stray_curve_view v = stray_curve_view_of(c);
	struct stray_exclusion ex;
	/* libstray's one verdict: NaN (JSON null) where not excluded */
	int k, rc = stray_exclusion_interval(&v, alpha_req, 1.0, &ex, err);

	if (rc != STRAY_OK)
		return rc;
	d->sun_deg = ex.theta_deg;
	d->sun_lo_deg = ex.excluded ? ex.theta_lo_deg : NAN;
	d->sun_hi_deg = ex.hi_reached ? ex.theta_hi_deg : NAN;
	for (k = 0; k < a->n_at; k++)
		d->alpha_at[k] = stray_curve_alpha_at(&v, a->at[k]);
	return rc;
}

static int make_state_dir(const char *dir, struct stray_error *err)
{
	if (mkdir(dir, 0777) == 0 || errno == EEXIST)
		return STRAY_OK;
	stray_error_set(err, STRAY_EIO, "--state", "cannot create folder");
	stray_error_text(err, dir);
	return STRAY_EIO;
}

/* A design as the runner sees it: its --set list (the fixed ones, then
 * the grid's), run key and state file. */
struct design_item {
	const char *sets[DESIGN_SWEEP_SETS_MAX];
	char set[GRID_AXES_MAX][2 * GRID_TEXT_MAX];
	char key[1100], path[4200];
	size_t design;
};

/* The sweep while its traces run: who is judged, who is reported. */
struct sweep_run {
	struct design_sweep *a;
	double alpha_req;
	struct design_item *items;	/* the designs to trace */
	unsigned char *ready;		/* per design: judged */
	size_t next_report;		/* progress in design order */
};

static void prepare(const struct design_sweep *a, size_t i,
		    struct design_item *it, struct design_result *d)
{
	int k, n = a->n_sets;

	design_grid_sets(&a->grid, i, it->set);
	design_grid_label(&a->grid, i, d->label, sizeof(d->label));
	for (k = 0; k < n; k++)
		it->sets[k] = a->sets[k];
	for (k = 0; k < a->grid.n_axes; k++)
		it->sets[n++] = it->set[k];
	run_key(a, d->label, it->key, sizeof(it->key));
	snprintf(it->path, sizeof(it->path), "%s/design_%04zu.csv", a->state,
		 i);
	it->design = i;
}

/* Progress for the designs judged so far, in design order (a farm
 * finishes them in any order; one process in order, as before). */
static void report(struct sweep_run *w)
{
	struct design_sweep *a = w->a;

	while (w->next_report < a->grid.n_designs &&
	       w->ready[w->next_report]) {
		if (a->progress)
			a->progress(a->progress_user, w->next_report,
				    a->grid.n_designs, &a->d[w->next_report]);
		w->next_report++;
	}
}

/* The runner's callback: keep item i's curve, judge it, report. */
static int design_done(void *user, size_t i, const struct tracer_result *r,
		       struct stray_error *err)
{
	struct sweep_run *w = user;
	const struct design_item *it = &w->items[i];
	struct stray_curve c;
	int rc = keep_curve(w->a, r, it->key, it->path, &c, err);

	if (rc)
		return rc;
	rc = judge(w->a, &c, w->alpha_req, &w->a->d[it->design], err);
	stray_curve_free(&c);
	w->ready[it->design] = 1;
	report(w);
	return rc;
}

/* Every design kept from an earlier run judged, the others traced
 * through the runner as one set. */
static int run_designs(struct sweep_run *w, struct stray_error *err)
{
	struct design_sweep *a = w->a;
	struct tracer_trace_item *set;
	struct tracer_trace_opts o = a->o;
	size_t i, n = 0;
	int rc = STRAY_OK;

	o.lens = a->lens ? &a->lens_model : NULL;
	set = calloc(a->grid.n_designs, sizeof(*set));
	w->items = calloc(a->grid.n_designs, sizeof(*w->items));
	w->ready = calloc(a->grid.n_designs, 1);
	if (!set || !w->items || !w->ready)
		rc = stray_error_set(err, STRAY_ENOMEM, "sweep",
				     "out of memory");
	for (i = 0; !rc && i < a->grid.n_designs; i++) {
		struct design_item *it = &w->items[n];
		struct stray_curve c;

		prepare(a, i, it, &a->d[i]);
		a->d[i].resumed = resume(it->path, it->key, &c);
		if (a->d[i].resumed) {
			rc = judge(a, &c, w->alpha_req, &a->d[i], err);
			stray_curve_free(&c);
			w->ready[i] = 1;
			continue;
		}
		set[n].spec.scene = a->scene;
		set[n].spec.sets = it->sets;
		set[n].spec.n_sets = a->n_sets + a->grid.n_axes;
		set[n].spec.lens = a->lens;
		set[n].o = &o;
		n++;
	}
	if (!rc) {
		report(w);
		rc = tracer_run_set(a->runner, set, n, design_done, w, err);
	}
	if (!rc)
		report(w);
	free(set);
	free(w->items);
	free(w->ready);
	return rc;
}

int design_sweep_run(struct design_sweep *a, double alpha_req,
		     struct stray_error *err)
{
	struct sweep_run w;
	size_t n;
	int rc = make_angles(a, &a->theta, &n, err);

	memset(&w, 0, sizeof(w));
	w.a = a;
	w.alpha_req = alpha_req;
	if (!rc && a->lens)
		rc = tracer_lens_load(a->lens, &a->lens_model, err);
	if (!rc)
		rc = make_state_dir(a->state, err);
	a->d = calloc(a->grid.n_designs, sizeof(*a->d));
	if (!rc && !a->d)
		rc = stray_error_set(err, STRAY_ENOMEM, "sweep", "out of memory");
	a->o.theta_deg = a->theta;
	a->o.n_theta = n;
	if (!rc)
		rc = run_designs(&w, err);
	blame_grid(a, err);
	return rc;
}

void design_sweep_free(struct design_sweep *a)
{
	free(a->d);
	free(a->theta);
	tracer_lens_free(&a->lens_model);
	a->d = NULL;
	a->theta = NULL;
}
