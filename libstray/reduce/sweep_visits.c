/*
 * sweep_visits.c - the visits of a sweep: the manifest's runs paired into
 * visits, each visit's FULL and AMBIENT groups accumulated to J (eq. 3.6),
 * the frame-common noise and the drift, the commanded angles, and the
 * ghost tracks over the visits in increasing theta.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/reduce_angle.h"
#include "stray/reduce_common.h"
#include "stray/sweep_store.h"
#include "stray/reduce_sweep.h"
#include "bigmem.h"
#include "prefetch.h"
#include "sweep_ws.h"

/* Runs of consecutive non-dark manifest rows at one angle. */
static size_t find_runs(struct workspace *w)
{
	size_t i, n = 0;
	double cur = 0.0;

	for (i = 0; i < w->man.n; i++) {
		const struct stray_sweep_entry *e = &w->man.e[i];
		struct visit_plan *p;

		if (e->type == STRAY_SWEEP_DARK)
			continue;
		if (n == 0 || fabs(e->angle_deg - cur) > STRAY_THETA_TOL_DEG) {
			w->plan[n].first[0] = i;
			w->plan[n].n_runs = 1;
			cur = e->angle_deg;
			n++;
		}
		p = &w->plan[n - 1];
		p->last[0] = i;
		p->n_full += e->type == STRAY_SWEEP_FULL;
		p->n_amb += e->type == STRAY_SWEEP_AMBIENT;
	}
	return n;
}

/* Pair each FULL-only run with the next AMBIENT-only run at its angle
 * (or the reverse), then drop the runs taken. */
static size_t pair_runs(struct workspace *w, size_t n)
{
	size_t i, k, kept = 0;

	for (i = 0; i < n; i++) {
		struct visit_plan *p = &w->plan[i];

		if (p->n_runs == 0 || (p->n_full && p->n_amb))
			continue;
		for (k = i + 1; k < n; k++) {
			struct visit_plan *q = &w->plan[k];
			double a = w->man.e[p->first[0]].angle_deg;
			double b = w->man.e[q->first[0]].angle_deg;

			if (q->n_runs == 1 && fabs(a - b) <= STRAY_THETA_TOL_DEG &&
			    !(q->n_full && q->n_amb) &&
			    !!q->n_full != !!p->n_full) {
				p->first[1] = q->first[0];
				p->last[1] = q->last[0];
				p->n_full += q->n_full;
				p->n_amb += q->n_amb;
				p->n_runs = 2;
				q->n_runs = 0;	/* taken */
				break;
			}
		}
	}
	for (i = 0; i < n; i++)
		if (w->plan[i].n_runs)
			w->plan[kept++] = w->plan[i];
	return kept;
}

/* Visits: a run of one angle's FULL and AMBIENT frames, or two
 * (planned before the darks are read: the read order needs it). */
int stray_rs_plan_visits(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err)
{
	w->plan = calloc(w->man.n, sizeof(*w->plan));
	res->visits = calloc(w->man.n, sizeof(*res->visits));
	if (!w->plan || !res->visits)
		return stray_error_set(err, STRAY_ENOMEM, "manifest",
				       "no memory for the visit plan");
	res->n_visits = pair_runs(w, find_runs(w));
	return STRAY_OK;
}

/* ... and said to be empty where the darks are done. */
int stray_rs_check_visits(struct workspace *w,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err)
{
	if (res->n_visits == 0)
		return stray_error_at(err, STRAY_ENOTFOUND, w->man.n ?
			"manifest.csv" : "", 0, "frametyp",
			"no FULL or AMBIENT frames in the sweep");
	return STRAY_OK;
}

int stray_rs_light_buffers(struct workspace *w,
			   struct stray_reduce_sweep_result *res,
			   struct stray_error *err)
{
	size_t ab = stray_accum_bytes(w->n_pix), nc = w->geo.n_cols;
	size_t fb = w->n_pix * sizeof(float);

	w->acc_mem[0] = stray_rs_ws_take(w, ab, 0);
	w->acc_mem[1] = stray_rs_ws_take(w, ab, ab);
	w->j = stray_rs_ws_take(w, fb, 2 * ab);
	w->var_j = stray_rs_ws_take(w, fb, 2 * ab + fb);
	w->prof_var = calloc(nc, sizeof(double));
	w->ghost_scratch = calloc(stray_ghost_scratch(nc, &w->o->ghost),
				  sizeof(double));
	res->profiles = calloc(res->n_visits * nc, sizeof(double));
	if (!w->acc_mem[0] || !w->acc_mem[1] || !w->j || !w->var_j ||
	    !w->prof_var || !w->ghost_scratch || !res->profiles)
		return stray_error_set(err, STRAY_ENOMEM, "frame",
				       "no memory for the accumulators");
	stray_accum_init(&w->full, w->n_pix, w->acc_mem[0]);
	stray_accum_init(&w->amb, w->n_pix, w->acc_mem[1]);
	return STRAY_OK;
}

/* Stream one visit's frames into the FULL and AMBIENT accumulators. */
static int accumulate_visit(struct workspace *w, struct visit_plan *p,
			    struct stray_reduce_sweep_result *res, struct stray_error *err)
{
	struct stray_frame f;
	size_t i, r;
	int rc = STRAY_OK;

	stray_accum_reset(&w->full);
	stray_accum_reset(&w->amb);
	stray_common_group_reset(&p->cg[0]);
	stray_common_group_reset(&p->cg[1]);
	for (r = 0; r < p->n_runs; r++)
		for (i = p->first[r]; i <= p->last[r] && rc == STRAY_OK; i++) {
			const struct stray_sweep_entry *e = &w->man.e[i];

			if (e->type == STRAY_SWEEP_DARK)
				continue;
			rc = stray_rs_load_frame(w, e, &f, w->pix, err);
			if (rc == STRAY_OK) {
				p->rb_sum += w->fits.h.angle_rb_deg;
				p->n_rb++;
			}
			if (rc == STRAY_OK)
				rc = stray_rs_at_frame(w, e, stray_accum_add(
					e->type == STRAY_SWEEP_FULL ? &w->full : &w->amb,
					&w->dark, &f, err), err);
			if (rc == STRAY_OK)
				rc = stray_rs_at_frame(w, e,
					stray_common_group_add(
					&p->cg[e->type != STRAY_SWEEP_FULL],
					&w->dark, &f, w->mask, (double)i,
					err), err);
			res->has_monitor |= w->fits.h.has_monitor;
		}
	return rc;
}

static int keep_image(struct workspace *w, double theta,
		      struct stray_reduce_sweep_result *res, struct stray_error *err)
{
	if (!w->o->keep_image || res->image ||
	    fabs(theta - w->o->image_theta_deg) > STRAY_THETA_TOL_DEG)
		return STRAY_OK;
	res->image = malloc(w->n_pix * sizeof(float));
	if (!res->image)
		return stray_error_set(err, STRAY_ENOMEM, "image",
				       "no memory for the J image");
	memcpy(res->image, w->j, w->n_pix * sizeof(float));
	res->image_theta_deg = theta;
	return STRAY_OK;
}

/* A visit's place in manifest rows: the middle of its frames. */
static double row_order(const struct visit_plan *p)
{
	return p->n_runs == 1 ?
		0.5 * ((double)p->first[0] + (double)p->last[0]) :
		0.25 * ((double)p->first[0] + (double)p->last[0] +
			(double)p->first[1] + (double)p->last[1]);
}

/* A manifest row's time, s after the sweep's first frame. */
static double when(const struct workspace *w, size_t i)
{
	return w->man.e[i].date_obs - w->man.e[0].date_obs;
}

/* Whether every row has a time (then the drift is fitted in time). */
int stray_rs_all_timed(const struct workspace *w, double *span)
{
	double lo = HUGE_VAL, hi = -HUGE_VAL;
	size_t i;

	for (i = 0; i < w->man.n; i++) {
		double t = w->man.e[i].date_obs;

		if (!(isfinite(t) && t > 0))
			return 0;
		lo = fmin(lo, t);
		hi = fmax(hi, t);
	}
	*span = w->man.n ? hi - lo : 0;
	return w->man.n > 0;
}

int stray_rs_reduce_visit(struct workspace *w, size_t v,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err)
{
	struct visit_plan *p = &w->plan[v];
	const struct stray_sweep_entry *e0 = &w->man.e[p->first[0]];
	struct stray_frame geo = { 0 };
	struct stray_response_sums s;
	struct stray_visit *vis = &res->visits[v];
	double *prof = res->profiles + v * w->geo.n_cols;
	int rc;

	if ((rc = accumulate_visit(w, p, res, err)) != STRAY_OK)
		return rc;
	geo.n_rows = w->geo.n_rows;
	geo.n_cols = w->geo.n_cols;
	rc = stray_response_compute(&w->full, &w->amb, &w->dark, w->mask,
				    &geo, &w->o->response, w->j, w->var_j,
				    &s, err);
	if (rc != STRAY_OK)
		return stray_rs_at_frame(w, e0, rc, err);
	vis->theta_deg = e0->angle_deg;
	/* Acquisition order: the middle of the visit's frames, in time when
	 * the folder has it (a pause, a kill and a resume, a night are then
	 * as long as they were), else in manifest rows. */
	vis->order = !res->drift_in_time ? row_order(p) :
		p->n_runs == 1 ?
		0.5 * (when(w, p->first[0]) + when(w, p->last[0])) :
		0.25 * (when(w, p->first[0]) + when(w, p->last[0]) +
			when(w, p->first[1]) + when(w, p->last[1]));
	vis->power = s.power;
	vis->var_power = s.var_power;
	vis->sigma = s.sigma;
	stray_common_group_finish(&p->cg[0], &s.var[0]);
	stray_common_group_finish(&p->cg[1], &s.var[1]);
	vis->n_pix = s.n_pix;
	res->n_sat_samples += w->full.n_sat + w->amb.n_sat;
	res->n_sat_pixels += s.n_sat_pix;
	stray_response_profile(w->j, w->var_j, geo.n_rows, geo.n_cols, prof,
			       w->prof_var);
	p->n_peaks = stray_ghost_find(prof, w->prof_var, geo.n_cols,
				      &w->o->ghost, w->ghost_scratch, p->peaks,
				      STRAY_GHOST_PEAKS_MAX);
	return keep_image(w, vis->theta_deg, res, err);
}

static const struct stray_visit *sort_base;

static int by_theta(const void *a, const void *b)
{
	const struct stray_visit *x = &sort_base[*(const size_t *)a];
	const struct stray_visit *y = &sort_base[*(const size_t *)b];

	if (x->theta_deg != y->theta_deg)
		return (x->theta_deg > y->theta_deg) - (x->theta_deg < y->theta_deg);
	return (x->order > y->order) - (x->order < y->order);
}

/* Feed the first visit of every angle, in increasing theta, to a tracker. */
int stray_rs_track_ghosts(struct workspace *w,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err)
{
	struct stray_ghost_tracker t;
	size_t *idx = malloc(res->n_visits * sizeof(*idx)), i;
	double last = -HUGE_VAL;

	if (!idx)
		return stray_error_set(err, STRAY_ENOMEM, "ghosts",
				       "no memory");
	for (i = 0; i < STRAY_REDUCE_TRACKS_MAX; i++) {
		res->tracks[i].pt = calloc(res->n_visits,
					   sizeof(*res->tracks[i].pt));
		res->tracks[i].cap = res->n_visits;
		if (!res->tracks[i].pt) {
			free(idx);
			return stray_error_set(err, STRAY_ENOMEM, "ghosts",
					       "no memory");
		}
	}
	for (i = 0; i < res->n_visits; i++)
		idx[i] = i;
	sort_base = res->visits;
	qsort(idx, res->n_visits, sizeof(*idx), by_theta);
	stray_ghost_tracker_init(&t, &w->o->ghost, res->tracks,
				 STRAY_REDUCE_TRACKS_MAX);
	for (i = 0; i < res->n_visits; i++) {
		const struct stray_visit *v = &res->visits[idx[i]];

		if (v->theta_deg <= last + STRAY_THETA_TOL_DEG)
			continue;
		last = v->theta_deg;
		stray_ghost_tracker_add(&t, v->theta_deg, w->plan[idx[i]].peaks,
					w->plan[idx[i]].n_peaks,
					(double)w->geo.n_rows, v->power);
	}
	res->n_tracks = stray_ghost_tracker_finish(&t);
	free(idx);
	return STRAY_OK;
}

/* The fitted source drift per manifest row, relative (0: none fitted):
 * over the on-axis visits' row span, however the fit measured it (the
 * frame-common noise works within groups, in rows). */
static double drift_per_row(const struct workspace *w,
			    const struct stray_reduce_sweep_result *res)
{
	double lo = HUGE_VAL, hi = -HUGE_VAL;
	size_t v;

	if (!res->drift.fitted)
		return 0.0;
	for (v = 0; v < res->n_visits; v++)
		if (fabs(res->visits[v].theta_deg) <= STRAY_THETA_TOL_DEG) {
			lo = fmin(lo, row_order(&w->plan[v]));
			hi = fmax(hi, row_order(&w->plan[v]));
		}
	return hi > lo ? res->drift.rel_change / (hi - lo) : 0.0;
}

/*
 * Frame-common noise (reduce_common.h), measured with the drift of the
 * first curve taken out of each group, then s^2 Sbar^2 / n of every group
 * added to its visit's var(P); *redo when the curve must be redone.
 */
int stray_rs_add_common(struct workspace *w,
			struct stray_reduce_sweep_result *res, int *redo,
			struct stray_error *err)
{
	size_t n = 2 * res->n_visits, v, g;
	double *est = malloc(n * sizeof(*est)), *ind = malloc(n * sizeof(*ind));
	size_t *dof = malloc(n * sizeof(*dof));
	double s2, beta = drift_per_row(w, res);

	*redo = 0;

	if (!est || !ind || !dof) {
		free(est);
		free(ind);
		free(dof);
		return stray_error_set(err, STRAY_ENOMEM, "curve", "no memory");
	}
	res->common_dof = 0;
	for (v = 0; v < res->n_visits; v++)
		for (g = 0; g < 2; g++) {
			size_t k = 2 * v + g;

			dof[k] = stray_common_group_stats(&w->plan[v].cg[g],
				beta, &est[k], &ind[k]);
			res->common_dof += dof[k];
		}
	s2 = stray_common_fit(est, ind, dof, n);
	free(est);
	free(ind);
	free(dof);
	res->common_rel_sigma = sqrt(s2);
	if (w->o->no_common || !(s2 > 0.0))
		return STRAY_OK;
	for (v = 0; v < res->n_visits; v++)
		for (g = 0; g < 2; g++) {
			const struct stray_common_group *c = &w->plan[v].cg[g];
			double m = stray_common_group_mean(c);

			if (c->n > 0)
				res->visits[v].var_power +=
					s2 * m * m / (double)c->n;
		}
	*redo = 1;
	return STRAY_OK;
}

/* Visits taken off their commanded angle (ANGLERB, reduce_angle.h):
 * carried there along the curve; 1 when the curve must be redone. */
int stray_rs_to_commanded(struct workspace *w,
			  struct stray_reduce_sweep_result *res)
{
	double *rb = malloc(res->n_visits * sizeof(*rb));
	size_t v;

	if (!rb || w->o->no_angle_rb) {
		free(rb);
		return 0;
	}
	for (v = 0; v < res->n_visits; v++)
		rb[v] = w->plan[v].n_rb ? w->plan[v].rb_sum /
			(double)w->plan[v].n_rb : res->visits[v].theta_deg;
	res->angle_rb_max_deg = stray_visits_to_commanded(res->visits,
		res->n_visits, rb, res->points, res->n_points);
	free(rb);
	return res->angle_rb_max_deg > 0.0;
}
