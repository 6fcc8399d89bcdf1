/*
 * sweep.c - the sweep engine (sweep.h).  Order per angle: FULL frames,
 * AMBIENT frames, then DARK frames at each exposure those used (eq. 3.4-
 * 3.5: the dark must match the exposure time), `repeats` each.  What to
 * take next is always derived from manifest.csv, never from memory, so a
 * resumed sweep cannot skip, repeat or mislabel a frame.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig/sweep.h"
#include "stray/errfmt.h"

#define MAX_ANGLES 100000

/* A sweep-store failure as the rig's one error line. */
static int store_fail(struct rig_error *err, const struct stray_error *se)
{
	char line[RIG_ERROR_MSG_MAX];
	int code = se->code == STRAY_ENOMEM ? RIG_ENOMEM :
		   se->code == STRAY_EPARSE || se->code == STRAY_ENOTFOUND
		   ? RIG_EPARSE : RIG_EIO;

	return rig_error_set(err, code, "%s",
			     stray_error_format(se, line, sizeof(line)));
}

int rig_sweep_angles(const struct rig_sweep_cfg *cfg, double **angles,
		     int *n, struct rig_error *err)
{
	double span = cfg->theta_stop_deg - cfg->theta_start_deg;
	long k, count = cfg->n_list > 0 ? cfg->n_list :
		(long)floor(span / cfg->theta_step_deg + 1e-9) + 1;

	if (cfg->n_list == 0 && (!(cfg->theta_step_deg > 0) || span < 0 ||
				 count > MAX_ANGLES))
		return rig_error_set(err, RIG_EINVAL,
			"sweep: angles %g..%g step %g give no valid list",
			cfg->theta_start_deg, cfg->theta_stop_deg,
			cfg->theta_step_deg);
	*angles = malloc((size_t)count * sizeof(**angles));
	if (!*angles)
		return rig_error_set(err, RIG_ENOMEM, "sweep: no memory");
	/* To the 0.001 deg of the frame names, so memory, manifest and
	 * files name one angle alike. */
	for (k = 0; k < count; k++)
		(*angles)[k] = round(1e3 * (cfg->n_list > 0 ? cfg->list[k] :
			cfg->theta_start_deg + k * cfg->theta_step_deg)) / 1e3;
	*n = (int)count;
	return RIG_OK;
}

/* Frames of one visit: angles[i] may come back in a list, each return
 * a visit of its own whose seqnums follow the earlier visits' (FULL and
 * AMBIENT by repeats, DARK by 2 x repeats: up to two exposures). */
static int visit_count(const struct rig_sweep *sw, int i, int type,
		       const struct stray_sweep_entry **first, long *base)
{
	long span = (type == STRAY_SWEEP_DARK ? 2L : 1L) * sw->cfg->repeats;
	long lo = span * sw->visit_no[i];
	size_t k;
	int n = 0;

	if (first)
		*first = NULL;
	if (base)
		*base = lo;
	for (k = 0; k < sw->mf.n; k++) {
		const struct stray_sweep_entry *e = &sw->mf.e[k];

		if (e->type != type || fabs(e->angle_deg - sw->angles[i]) >
		    5e-4 || e->seqnum < lo || e->seqnum >= lo + span)
			continue;
		if (first && !*first)
			*first = e;
		n++;
	}
	return n;
}

/* Which visit of its angle each list entry is (0 = the first). */
static int number_visits(struct rig_sweep *sw, struct rig_error *err)
{
	int i, j;

	sw->visit_no = calloc((size_t)sw->n_angles, sizeof(*sw->visit_no));
	if (!sw->visit_no)
		return rig_error_set(err, RIG_ENOMEM, "sweep: no memory");
	for (i = 0; i < sw->n_angles; i++)
		for (j = 0; j < i; j++)
			sw->visit_no[i] += fabs(sw->angles[j] -
						sw->angles[i]) < 5e-4;
	return RIG_OK;
}

static int slot_of(const struct rig_wheel_cfg *w, double nd);

/* A resumed sweep starts each exposure search where the last angle's
 * ended, as an uninterrupted one would. */
static void seed_settings(struct rig_sweep *sw)
{
	size_t i;

	for (i = 0; i < sw->mf.n; i++) {
		const struct stray_sweep_entry *m = &sw->mf.e[i];

		if (m->type == STRAY_SWEEP_DARK)
			continue;
		sw->t_exp_s[m->type] = m->exptime_s;
		sw->slot[m->type] = slot_of(&sw->lab->cfg->wheel, m->ndtrans);
	}
}

int rig_sweep_claim(struct rig_sweep *sw, const struct rig_config *cfg,
		    const char *dir, int flags, struct rig_error *err)
{
	return rig_sweep_claim_as(sw, cfg, dir, flags, NULL, err);
}

int rig_sweep_claim_as(struct rig_sweep *sw, const struct rig_config *cfg,
		       const char *dir, int flags, const char *owner,
		       struct rig_error *err)
{
	struct stray_error se;
	long planned;
	int rc;

	memset(sw, 0, sizeof(*sw));
	snprintf(sw->owner, sizeof(sw->owner), "%s", owner ? owner : "?");
	sw->cfg = &cfg->sweep;
	rc = rig_sweep_angles(sw->cfg, &sw->angles, &sw->n_angles, err);
	if (rc == RIG_OK)
		rc = number_visits(sw, err);
	if (rc != RIG_OK) {
		rig_sweep_close(sw);
		return rc;
	}
	/* The disk from the plan, before a frame is taken: every frame
	 * of a new sweep, the rest of a resumed one. */
	planned = (long)sw->n_angles * 4 * sw->cfg->repeats;
	if (!(flags & RIG_SWEEP_RESUME) &&
	    (rc = rig_sweep_space_check(dir, cfg, planned, err)) != RIG_OK) {
		rig_sweep_close(sw);
		return rc;
	}
	stray_error_clear(&se);
	if (stray_sweep_store_open(&sw->mf, dir, flags & RIG_SWEEP_RESUME,
				   &se) != STRAY_OK) {
		rig_sweep_close(sw);
		return store_fail(err, &se);
	}
	if ((flags & RIG_SWEEP_RESUME) &&
	    (rc = rig_sweep_space_check(dir, cfg, planned > (long)sw->mf.n ?
					planned - (long)sw->mf.n : 0, err)) !=
	    RIG_OK) {
		rig_sweep_close(sw);
		return rc;
	}
	/* The lock is ours: the plan cannot change under us. */
	rc = rig_sweep_plan_check_as(dir, cfg, flags & RIG_SWEEP_FORCE_PLAN,
				     owner, err);
	if (rc != RIG_OK)
		rig_sweep_close(sw);
	return rc;
}

int rig_sweep_attach(struct rig_sweep *sw, struct rig_lab *lab,
		     struct rig_error *err)
{
	const struct rig_camera_cfg *cam = &lab->cfg->camera;
	size_t i;

	sw->lab = lab;
	sw->img.px = malloc((size_t)cam->n_rows * cam->n_cols *
			    sizeof(*sw->img.px));
	if (!sw->img.px) {
		rig_sweep_close(sw);
		return rig_error_set(err, RIG_ENOMEM, "sweep: no memory");
	}
	seed_settings(sw);
	for (i = 0; i < sw->mf.n; i++)
		if (sw->mf.e[i].date_obs > sw->utc_floor)
			sw->utc_floor = sw->mf.e[i].date_obs;
	sw->done_at_open = (long)sw->mf.n;
	sw->t_open_s = rig_hal_now(lab->hal);
	return RIG_OK;
}

int rig_sweep_open(struct rig_sweep *sw, struct rig_lab *lab,
		   const char *dir, int flags, struct rig_error *err)
{
	return rig_sweep_open_as(sw, lab, dir, flags, NULL, err);
}

int rig_sweep_open_as(struct rig_sweep *sw, struct rig_lab *lab,
		      const char *dir, int flags, const char *owner,
		      struct rig_error *err)
{
	int rc = rig_sweep_claim_as(sw, lab->cfg, dir, flags, owner, err);

	return rc == RIG_OK ? rig_sweep_attach(sw, lab, err) : rc;
}

static int slot_of(const struct rig_wheel_cfg *w, double nd)
{
	int k, best = 0;

	for (k = 1; k < w->n_slots; k++)
		if (fabs(log(w->trans[k] / nd)) <
		    fabs(log(w->trans[best] / nd)))
			best = k;
	return best;
}

/* Exposure and slot for a lit frame type at the current angle: from the
 * manifest if the group has begun, else by search, one test frame per
 * call; RIG_EAGAIN while the search goes on. */
static int lit_setting(struct rig_sweep *sw, int type, struct rig_error *err)
{
	const struct stray_sweep_entry *first;
	int rc, done;

	if (sw->have[type])
		return RIG_OK;
	if (visit_count(sw, sw->i_angle, type, &first, NULL) > 0) {
		sw->t_exp_s[type] = first->exptime_s;
		sw->slot[type] = slot_of(&sw->lab->cfg->wheel,
					 first->ndtrans);
	} else {
		if (sw->expo_it == 0 && !(sw->t_exp_s[type] > 0))
			sw->t_exp_s[type] = sw->cfg->t_init_s;
		rc = rig_expo_step(sw->lab, &sw->img, &sw->t_exp_s[type],
				   &sw->slot[type], &done, err);
		if (rc != RIG_OK)
			return rc;
		if (!done && ++sw->expo_it < RIG_EXPO_ITER_MAX)
			return RIG_EAGAIN;
	}
	sw->expo_it = 0;
	sw->have[type] = 1;
	return RIG_OK;
}

/* UTC through the HAL, never before the folder's last frame: a clock
 * stepped back (or a simulator restarted on its virtual clock) must not
 * put a frame before the ones it follows. */
static double utc_now(struct rig_sweep *sw)
{
	double t = rig_hal_utc(sw->lab->hal);

	return t > sw->utc_floor ? t : sw->utc_floor + 1e-3;
}

static int take(struct rig_sweep *sw, int type, int seq, double t_exp_s,
		struct rig_error *err)
{
	struct rig_lab *lab = sw->lab;
	struct stray_sweep_frame f;
	struct stray_sweep_image im;
	struct stray_sweep_key rb[RIG_SWEEP_RB_KEYS];
	struct stray_error se;
	int slot = lab->wheel.slot, rc;
	double t0 = 0;

	rc = rig_lab_illuminate(lab, type, err);
	if (rc == RIG_OK && type != STRAY_SWEEP_DARK)
		rc = rig_lab_wheel(lab, slot = sw->slot[type], err);
	if (rc == RIG_OK) {
		t0 = utc_now(sw);
		rc = rig_lab_capture(lab, t_exp_s, &sw->img, err);
	}
	memset(&f, 0, sizeof(f));
	f.date_obs = t0;
	f.date_end = utc_now(sw);
	sw->utc_floor = f.date_end;
	f.has_monitor = lab->cfg->monitor.enabled;
	if (rc == RIG_OK && f.has_monitor)
		rc = rig_lab_monitor(lab, &f.monitor, err);
	if (rc != RIG_OK)
		return rc;
	f.type = type;
	f.angle_deg = sw->angles[sw->i_angle];
	f.exptime_s = sw->img.t_exp_s;
	f.ndtrans = lab->cfg->wheel.trans[slot < 0 ? 0 : slot];
	f.seqnum = seq;
	f.sat_dn = lab->cfg->camera.sat_dn;
	f.full_frame = sw->img.n_rows == RIG_FL_SENSOR_ROWS;
	f.extra = rb;
	f.n_extra = rig_sweep_readback_keys(lab, rb);
	im.n_rows = (size_t)sw->img.n_rows;
	im.n_cols = (size_t)sw->img.n_cols;
	im.col0 = sw->img.col0;
	im.rows = sw->img.rows;
	im.px = sw->img.px;
	stray_error_clear(&se);
	if (stray_sweep_store_append(&sw->mf, &f, &im, &se) != STRAY_OK)
		return store_fail(err, &se);
	sw->taken++;
	return RIG_OK;
}

/* Exposures the darks at this angle must match: FULL's, then AMBIENT's
 * when it differs. */
static int dark_exposures(const struct rig_sweep *sw, int i, double t[2])
{
	const struct stray_sweep_entry *f, *a;

	visit_count(sw, i, STRAY_SWEEP_FULL, &f, NULL);
	visit_count(sw, i, STRAY_SWEEP_AMBIENT, &a, NULL);
	t[0] = f->exptime_s;
	t[1] = a->exptime_s;
	return fabs(t[0] - t[1]) < 1e-9 ? 1 : 2;
}

static void next_angle(struct rig_sweep *sw)
{
	sw->i_angle++;
	sw->at_angle = 0;
	memset(sw->have, 0, sizeof(sw->have));
}

/* The frame to take next at the current angle; 0 when all are taken. */
static int plan(struct rig_sweep *sw, int *type, int *seq, double *t)
{
	static const int lit[2] = { STRAY_SWEEP_FULL, STRAY_SWEEP_AMBIENT };
	int reps = sw->cfg->repeats, k, n, nd, i = sw->i_angle;
	double td[2];
	long base;

	for (k = 0; k < 2; k++) {
		n = visit_count(sw, i, lit[k], NULL, &base);
		if (n < reps) {
			*type = lit[k];
			*seq = (int)base + n;
			*t = -1;	/* from lit_setting */
			return 1;
		}
	}
	nd = dark_exposures(sw, i, td);
	n = visit_count(sw, i, STRAY_SWEEP_DARK, NULL, &base);
	if (n >= reps * nd)
		return 0;
	*type = STRAY_SWEEP_DARK;
	*seq = (int)base + n;
	*t = td[n / reps];
	return 1;
}

static int step_once(struct rig_sweep *sw, struct rig_error *err)
{
	int type, seq, rc;
	double t;

	while (sw->i_angle < sw->n_angles && !plan(sw, &type, &seq, &t))
		next_angle(sw);
	if (sw->i_angle >= sw->n_angles) {
		sw->finished = 1;
		return rig_lab_safe(sw->lab, err);
	}
	/* The stage may have been moved (an operator's move while the
	 * sweep was held after a fault) or lost (a reconnect): go back. */
	if (!sw->at_angle ||
	    !(fabs(sw->lab->theta_deg - sw->angles[sw->i_angle]) < 1e-9)) {
		rc = rig_lab_move(sw->lab, sw->angles[sw->i_angle], err);
		if (rc != RIG_OK)
			return rc;
		sw->at_angle = 1;
	}
	if (type != STRAY_SWEEP_DARK) {
		rc = rig_lab_illuminate(sw->lab, type, err);
		if (rc == RIG_OK)
			rc = lit_setting(sw, type, err);
		if (rc == RIG_EAGAIN)
			return RIG_OK;	/* a test frame taken: step again */
		if (rc != RIG_OK)
			return rc;
		t = sw->t_exp_s[type];
	}
	return take(sw, type, seq, t, err);
}

int rig_sweep_step(struct rig_sweep *sw, struct rig_error *err)
{
	int rc;

	double t0;

	if (sw->finished)
		return RIG_OK;
	t0 = rig_hal_now(sw->lab->hal);
	rc = step_once(sw, err);
	sw->busy_s += rig_hal_now(sw->lab->hal) - t0;
	sw->steps++;
	if (rc != RIG_OK) {
		struct rig_error ignore;

		rig_error_clear(&ignore);
		rig_lab_safe(sw->lab, &ignore);
	}
	return rc;
}

/* The frame the next step works on, in words. */
static void describe_step(const struct rig_sweep *sw, char *out, size_t size)
{
	struct rig_sweep tmp = *sw;	/* plan() looks, never changes */
	int type, seq, reps = sw->cfg->repeats;
	double t, td[2];
	long base;

	while (tmp.i_angle < tmp.n_angles && !plan(&tmp, &type, &seq, &t))
		tmp.i_angle++;
	if (sw->finished || tmp.i_angle >= tmp.n_angles) {
		snprintf(out, size, "finished");
		return;
	}
	visit_count(&tmp, tmp.i_angle, type, NULL, &base);
	if (type != STRAY_SWEEP_DARK && seq == base &&
	    !(tmp.i_angle == sw->i_angle && sw->have[type]))
		snprintf(out, size, "%s exposure search at %.3f deg",
			 stray_sweep_frametyp_name(type),
			 tmp.angles[tmp.i_angle]);
	else {
		snprintf(out, size, "%s %ld of %d at %.3f deg%s",
			 stray_sweep_frametyp_name(type), seq - base + 1,
			 type == STRAY_SWEEP_DARK
			 ? reps * dark_exposures(&tmp, tmp.i_angle, td)
			 : reps, tmp.angles[tmp.i_angle],
			 sw->visit_no[tmp.i_angle] ? " (a return)" : "");
	}
}

void rig_sweep_progress(const struct rig_sweep *sw, struct rig_progress *p)
{
	int reps = sw->cfg->repeats, k;
	double rate;

	memset(p, 0, sizeof(*p));
	p->done = (long)sw->mf.n;
	/* Angles not yet finished count 4 groups (two dark exposures)
	 * until their exposures are known. */
	for (k = 0; k < sw->n_angles; k++) {
		int nf = visit_count(sw, k, STRAY_SWEEP_FULL, NULL, NULL);
		int na = visit_count(sw, k, STRAY_SWEEP_AMBIENT, NULL, NULL);
		double td[2];

		p->total += reps * 2 + (nf >= reps && na >= reps
			? reps * dark_exposures(sw, k, td) : reps * 2);
	}
	p->elapsed_s = rig_hal_now(sw->lab->hal) - sw->t_open_s;
	/* Time per frame kept from the time spent stepping, test frames and
	 * moves included, pauses and faults not: a mean over the run, so
	 * the ETA settles instead of jumping with each exposure search. */
	rate = sw->taken > 0 ? sw->busy_s / sw->taken : 0;
	p->eta_s = rate * (double)(p->total - p->done);
	p->percent = p->total > 0 ? 100.0 * p->done / p->total : 0;
	p->n_angles = sw->n_angles;
	p->angle_no = sw->i_angle < sw->n_angles ? sw->i_angle + 1
						 : sw->n_angles;
	describe_step(sw, p->step, sizeof(p->step));
	/* Past the end (finished, or resumed when already complete) the
	 * sweep's angle is its last, never NaN. */
	p->theta_deg = sw->n_angles == 0 ? 0
		       : sw->angles[sw->i_angle < sw->n_angles ? sw->i_angle
							     : sw->n_angles - 1];
	p->finished = sw->finished;
}

int rig_sweep_run(struct rig_sweep *sw, FILE *out, struct rig_error *err)
{
	struct rig_progress p;
	int rc = RIG_OK;

	while (!sw->finished && rc == RIG_OK) {
		rc = rig_sweep_step(sw, err);
		if (out && rc == RIG_OK) {
			rig_sweep_progress(sw, &p);
			fprintf(out, "sweep: %ld/%ld frames, theta %.3f deg, "
				"elapsed %.1f s, eta %.1f s\n", p.done, p.total,
				p.theta_deg, p.elapsed_s, p.eta_s);
		}
	}
	return rc;
}

void rig_sweep_close(struct rig_sweep *sw)
{
	stray_sweep_manifest_free(&sw->mf);
	free(sw->angles);
	free(sw->visit_no);
	free(sw->img.px);
	sw->visit_no = NULL;
	sw->angles = NULL;
	sw->img.px = NULL;
}
