/*
 * sweep.c - stray_reduce_sweep (reduce_sweep.h): stream a sweep folder,
 * read through the sweep store (sweep_store.h), through the reduction of
 * thesis §3.2: darks (levels per read channel, then hot/dead pixels),
 * then every visit to an angle (FULL and AMBIENT groups -> J, eq. 3.6),
 * then the curve (eq. 3.12-3.15) and the ghost tracks.
 *
 * Reading (issue 19): every frame file is read once, whole; its SHA-256
 * is taken of those bytes (unless verify_sha256 is off) and cfitsio
 * decodes the same bytes from memory.  A second thread (prefetch.c)
 * reads and hashes the next frame while this one is decoded and
 * accumulated.  The darks of pass 1 are decoded into
 * the part of the arena the pixel statistics leave free (up to
 * STRAY_REDUCE_DARK_CACHE), so pass 2 reads no file again; the phases
 * share that one arena, on 2 MiB pages (bigmem.c).  workspace_bytes
 * still counts the buffers each phase lays in it, as when each had its
 * own allocation.
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

/* Darks kept in memory between the two dark passes, at most. */
#define STRAY_REDUCE_DARK_CACHE 6

struct visit_plan {
	/* Manifest runs (darks skipped inside): the visit's own, and a run
	 * of the other type at the same angle when the sweep took all FULL
	 * frames in one pass and all AMBIENT frames in another. */
	size_t first[2], last[2], n_runs;
	size_t n_full, n_amb;
	size_t n_peaks;
	struct stray_ghost_peak peaks[STRAY_GHOST_PEAKS_MAX];
	/* Frame totals of its FULL [0] and AMBIENT [1] groups
	 * (reduce_common.h). */
	struct stray_common_group cg[2];
	double rb_sum;		/* ANGLERB (else ANGLE) over its light frames */
	size_t n_rb;
};

struct workspace {
	const char *dir;
	const struct stray_reduce_sweep_opts *o;
	struct stray_sweep_manifest man;
	struct stray_sweep_fits fits;		/* the frame being read */
	struct stray_sweep_buf file;	/* its bytes, when hashed */
	struct stray_prefetch pf;	/* the next ones, read and hashed */
	struct stray_sweep_header geo;	/* the first frame: the geometry */
	size_t n_pix;
	uint16_t *pix;
	struct stray_dark_model dark;
	uint8_t *mask;
	struct stray_accum full, amb;
	void *acc_mem[2];
	float *j, *var_j;
	double *prof_var, *ghost_scratch;
	struct visit_plan *plan;
	/* The phases' memory, and in it (beside the pixel statistics) the
	 * darks of pass 1 kept for pass 2. */
	unsigned char *arena;
	size_t arena_bytes, cache_at, cache_slots, n_cached;
	struct stray_frame cached[STRAY_REDUCE_DARK_CACHE];
	int monitor;		/* -1 unknown, else whether light frames
				 * carry MONITOR: all or none must */
	size_t bytes, peak_bytes;
};

void stray_reduce_sweep_opts_default(struct stray_reduce_sweep_opts *o)
{
	memset(o, 0, sizeof(*o));
	stray_bayer_default(&o->map);
	stray_ghost_opts_default(&o->ghost);
	o->hot_sigma = 6.0;
	o->verify_sha256 = 1;
}

/* Per-pixel allocation, counted toward the workspace bound. */
static void *ws_alloc(struct workspace *w, size_t bytes)
{
	void *p = stray_big_alloc(bytes);

	if (p) {
		w->bytes += bytes;
		if (w->bytes > w->peak_bytes)
			w->peak_bytes = w->bytes;
	}
	return p;
}

/*
 * A buffer of one phase, laid in the phase arena at offset at (the
 * darks' histograms, then their pixel statistics, then the light
 * accumulators: one after the other in the same memory), counted as
 * ws_alloc counts.
 */
static void *ws_take(struct workspace *w, size_t bytes, size_t at)
{
	w->bytes += bytes;
	if (w->bytes > w->peak_bytes)
		w->peak_bytes = w->bytes;
	return w->arena + at;
}

static void ws_give(struct workspace *w, size_t bytes)
{
	w->bytes -= bytes;
}

static int same(double a, double b, double rel)
{
	return fabs(a - b) <= rel * fmax(1.0, fmax(fabs(a), fabs(b)));
}

/* The header must say what the manifest says, and match the geometry. */
static int check_header(const struct workspace *w, const char *path,
			const struct stray_sweep_entry *e, const struct stray_sweep_header *h,
			struct stray_error *err)
{
	const char *key = NULL;

	if (h->type != e->type)
		key = "FRAMETYP";
	else if (!same(h->angle_deg, e->angle_deg, 1e-6))
		key = "ANGLE";
	else if (!same(h->exptime_s, e->exptime_s, 1e-6))
		key = "EXPTIME";
	else if (!same(h->ndtrans, e->ndtrans, 1e-6))
		key = "NDTRANS";
	if (key)
		return stray_error_at(err, STRAY_EINVAL, path, 0, key,
				      "differs from manifest.csv");
	if (h->n_cols != w->geo.n_cols)
		key = "NAXIS1";
	else if (h->n_rows != w->geo.n_rows)
		key = "NAXIS2";
	else if (h->col0 != w->geo.col0)
		key = "COL0";
	else if (memcmp(h->det_row, w->geo.det_row,
			h->n_rows * sizeof(h->det_row[0])) != 0)
		key = h->has_rows || w->geo.has_rows ? "ROWS" : "ROW0";
	if (key)
		return stray_error_at(err, STRAY_EINVAL, path, 0, key,
				      "differs from the sweep's first frame");
	return STRAY_OK;
}

static void frame_path(const struct workspace *w,
		       const struct stray_sweep_entry *e,
		       char *path, size_t size)
{
	snprintf(path, size, "%s/%s", w->dir, e->file);
}

/* Verify, open, check and read one frame into pix; fill f. */
static int load_frame(struct workspace *w, const struct stray_sweep_entry *e,
		      struct stray_frame *f, uint16_t *pix,
		      struct stray_error *err)
{
	char path[4096 + STRAY_SWEEP_FILE_MAX];
	int rc;

	struct stray_sweep_buf *b = &w->file;
	int taken = 0;

	frame_path(w, e, path, sizeof(path));
	/* Read once (ahead, by the prefetch thread, in its order), hashed
	 * from those bytes unless told not to, decoded from memory. */
	rc = stray_prefetch_take(&w->pf, e, &b, err);
	taken = rc == STRAY_OK;
	if (rc == STRAY_PREFETCH_NOT_NEXT) {
		b = &w->file;
		rc = stray_sweep_file_load(path, b, err);
		if (rc == STRAY_OK && w->o->verify_sha256)
			rc = stray_sweep_sha256_check_mem(path, b->data,
							  b->len, e->sha256,
							  err);
	}
	if (rc == STRAY_OK)
		rc = stray_sweep_fits_open_buf(path, b, &w->fits, err);
	if (rc != STRAY_OK) {
		if (taken)
			stray_prefetch_release(&w->pf);
		return rc;
	}
	rc = check_header(w, path, e, &w->fits.h, err);
	if (rc == STRAY_OK && e->type != STRAY_SWEEP_DARK) {
		if (w->monitor < 0)
			w->monitor = w->fits.h.has_monitor;
		else if (w->monitor != w->fits.h.has_monitor)
			rc = stray_error_at(err, STRAY_EINVAL, path, 0,
					    "MONITOR",
				"present in some light frames only");
	}
	if (rc == STRAY_OK)
		rc = stray_sweep_fits_read(&w->fits, pix, err);
	stray_sweep_fits_close(&w->fits);
	if (taken)
		stray_prefetch_release(&w->pf);
	if (rc != STRAY_OK)
		return rc;
	f->n_rows = w->geo.n_rows;
	f->n_cols = w->geo.n_cols;
	f->pix = pix;
	f->det_row = w->geo.det_row;
	f->col0 = w->geo.col0;
	f->t_exp_s = w->fits.h.exptime_s;
	f->nd_trans = w->fits.h.ndtrans;
	f->monitor = w->fits.h.monitor;
	f->sat_level = w->fits.h.satlevel;
	if (e->type != STRAY_SWEEP_DARK &&
	    stray_frame_clip_check(f, err) != STRAY_OK)
		return stray_error_locate(err, path, 0), STRAY_EINVAL;
	return STRAY_OK;
}

/* Library errors carry no file: name the frame. */
static int at_frame(struct workspace *w, const struct stray_sweep_entry *e,
		    int rc,
		    struct stray_error *err)
{
	char path[4096 + STRAY_SWEEP_FILE_MAX];

	if (rc != STRAY_OK) {
		frame_path(w, e, path, sizeof(path));
		stray_error_locate(err, path, 0);
	}
	return rc;
}

/*
 * The phases' arena: the largest of the darks' histograms, their pixel
 * statistics (mean, m2, scratch: 24 bytes a pixel) and the light
 * buffers (two accumulators, J and its variance: 28), with room after
 * the statistics' mean and m2 for up to STRAY_REDUCE_DARK_CACHE darks.
 */
static unsigned char *arena_alloc(struct workspace *w)
{
	size_t n = w->n_pix, frame = n * sizeof(uint16_t);
	size_t hist = STRAY_DARK_HIST_LEN * sizeof(uint32_t);
	size_t light = 2 * stray_accum_bytes(n) + 2 * n * sizeof(float);
	size_t stats = 3 * n * sizeof(double), a;

	w->cache_at = 2 * n * sizeof(double) > hist ? 2 * n * sizeof(double)
						     : hist;
	a = light > stats ? light : stats;
	if (a < w->cache_at + STRAY_REDUCE_DARK_CACHE * frame)
		a = w->cache_at + STRAY_REDUCE_DARK_CACHE * frame;
	w->cache_slots = (a - w->cache_at) / (frame ? frame : 1);
	if (w->cache_slots > STRAY_REDUCE_DARK_CACHE)
		w->cache_slots = STRAY_REDUCE_DARK_CACHE;
	w->arena_bytes = a;
	return stray_big_alloc(a);
}

/* Learn the geometry from the first frame and size the buffers. */
static int setup(struct workspace *w, struct stray_error *err)
{
	char path[4096 + STRAY_SWEEP_FILE_MAX];
	int rc;

	frame_path(w, &w->man.e[0], path, sizeof(path));
	if ((rc = stray_sweep_fits_open(path, &w->fits, err)) != STRAY_OK)
		return rc;
	w->geo = w->fits.h;
	stray_sweep_fits_close(&w->fits);
	w->n_pix = w->geo.n_rows * w->geo.n_cols;
	w->pix = ws_alloc(w, w->n_pix * sizeof(*w->pix));
	w->mask = ws_alloc(w, w->n_pix);
	w->arena = arena_alloc(w);
	if (!w->pix || !w->mask || !w->arena)
		return stray_error_set(err, STRAY_ENOMEM, "frame",
				       "no memory for the frame buffers");
	stray_dark_init(&w->dark, &w->o->map);
	return STRAY_OK;
}

/* Pass 1 over the darks: levels per channel and exposure time. */
static int dark_levels(struct workspace *w,
		       struct stray_reduce_sweep_result *res,
		       struct stray_error *err)
{
	uint32_t *hist = ws_take(w, STRAY_DARK_HIST_LEN * sizeof(*hist), 0);
	struct stray_frame f;
	size_t i;
	int rc = STRAY_OK;

	for (i = 0; i < w->man.n && rc == STRAY_OK; i++) {
		/* the first darks straight into the cache for pass 2 */
		int keep = w->n_cached < w->cache_slots;
		uint16_t *pix = keep ? (uint16_t *)(w->arena + w->cache_at) +
				w->n_cached * w->n_pix : w->pix;

		if (w->man.e[i].type != STRAY_SWEEP_DARK)
			continue;
		rc = load_frame(w, &w->man.e[i], &f, pix, err);
		if (rc == STRAY_OK)
			rc = at_frame(w, &w->man.e[i],
				      stray_dark_add(&w->dark, &f, hist, err),
				      err);
		if (rc == STRAY_OK && keep)
			w->cached[w->n_cached++] = f;
		res->n_darks++;
	}
	ws_give(w, STRAY_DARK_HIST_LEN * sizeof(*hist));
	stray_dark_finish(&w->dark);
	return rc;
}

static void list_pixels(const struct workspace *w,
			struct stray_reduce_sweep_result *res)
{
	size_t i;

	res->n_pixlist = 0;
	for (i = 0; i < w->n_pix && res->n_pixlist < STRAY_REDUCE_PIXLIST_MAX; i++) {
		struct stray_reduce_sweep_pixel *p = &res->pixlist[res->n_pixlist];

		if (w->mask[i] == STRAY_PIX_OK)
			continue;
		p->row = w->geo.det_row[i / w->geo.n_cols];
		p->col = w->geo.col0 + (long)(i % w->geo.n_cols);
		p->flag = w->mask[i];
		res->n_pixlist++;
	}
}

/* Pass 2 over the darks: hot and dead pixels. */
static int dark_pixels(struct workspace *w,
		       struct stray_reduce_sweep_result *res,
		       struct stray_error *err)
{
	size_t nb = w->n_pix * sizeof(double), i, k = 0;
	double *mean = ws_take(w, nb, 0), *m2 = ws_take(w, nb, nb);
	/* over the cached darks: used once they are done with */
	double *scratch = ws_take(w, nb, 2 * nb);
	struct stray_pixstat s;
	struct stray_frame f;
	int rc = STRAY_OK;

	stray_pixstat_init(&s, w->n_pix, mean, m2);
	for (i = 0; i < w->man.n && rc == STRAY_OK; i++) {
		if (w->man.e[i].type != STRAY_SWEEP_DARK)
			continue;
		if (k < w->n_cached)	/* pass 1 read, checked and kept it */
			f = w->cached[k++];
		else
			rc = load_frame(w, &w->man.e[i], &f, w->pix, err);
		if (rc == STRAY_OK)
			rc = at_frame(w, &w->man.e[i],
				      stray_pixstat_add(&s, &w->dark, &f, err),
				      err);
	}
	if (rc == STRAY_OK) {
		char path[4096 + 16];

		snprintf(path, sizeof(path), "%s/manifest.csv", w->dir);
		rc = stray_mask_build(&s, w->o->hot_sigma, w->mask, scratch,
				      &res->mask, err);
		if (rc != STRAY_OK)
			stray_error_locate(err, path, 0);
	}
	if (rc == STRAY_OK)
		list_pixels(w, res);
	ws_give(w, 3 * nb);
	return rc;
}

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
static int plan_visits(struct workspace *w,
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
static int check_visits(struct workspace *w,
			struct stray_reduce_sweep_result *res,
			struct stray_error *err)
{
	if (res->n_visits == 0)
		return stray_error_at(err, STRAY_ENOTFOUND, w->man.n ?
			"manifest.csv" : "", 0, "frametyp",
			"no FULL or AMBIENT frames in the sweep");
	return STRAY_OK;
}

static int light_buffers(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err)
{
	size_t ab = stray_accum_bytes(w->n_pix), nc = w->geo.n_cols;
	size_t fb = w->n_pix * sizeof(float);

	w->acc_mem[0] = ws_take(w, ab, 0);
	w->acc_mem[1] = ws_take(w, ab, ab);
	w->j = ws_take(w, fb, 2 * ab);
	w->var_j = ws_take(w, fb, 2 * ab + fb);
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
			rc = load_frame(w, e, &f, w->pix, err);
			if (rc == STRAY_OK) {
				p->rb_sum += w->fits.h.angle_rb_deg;
				p->n_rb++;
			}
			if (rc == STRAY_OK)
				rc = at_frame(w, e, stray_accum_add(
					e->type == STRAY_SWEEP_FULL ? &w->full : &w->amb,
					&w->dark, &f, err), err);
			if (rc == STRAY_OK)
				rc = at_frame(w, e, stray_common_group_add(
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
static int all_timed(const struct workspace *w, double *span)
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

static int reduce_visit(struct workspace *w, size_t v,
			struct stray_reduce_sweep_result *res, struct stray_error *err)
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
		return at_frame(w, e0, rc, err);
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
static int track_ghosts(struct workspace *w,
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

/*
 * The order load_frame will ask for frames in: the darks (pass 1), the
 * darks pass 1 could not keep (pass 2), then every visit's light frames.
 * Without memory for the list the frames are read as asked.
 */
static void start_reading(struct workspace *w,
			  const struct stray_reduce_sweep_result *res)
{
	const struct stray_sweep_entry **seq;
	size_t i, n = 0, n_dark = 0, v, r;

	seq = malloc((2 * w->man.n + 1) * sizeof(*seq));
	if (!seq)
		return;
	for (i = 0; i < w->man.n; i++)
		if (w->man.e[i].type == STRAY_SWEEP_DARK)
			seq[n++] = &w->man.e[i];
	for (i = 0; i < w->man.n; i++)
		if (w->man.e[i].type == STRAY_SWEEP_DARK &&
		    n_dark++ >= w->cache_slots)
			seq[n++] = &w->man.e[i];
	for (v = 0; v < res->n_visits; v++)
		for (r = 0; r < w->plan[v].n_runs; r++)
			for (i = w->plan[v].first[r]; i <= w->plan[v].last[r];
			     i++)
				if (w->man.e[i].type != STRAY_SWEEP_DARK)
					seq[n++] = &w->man.e[i];
	/* owns seq */
	stray_prefetch_start(&w->pf, w->dir, seq, n, w->o->verify_sha256);
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
static int add_common(struct workspace *w,
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
static int to_commanded(struct workspace *w,
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

static int reduce_all(struct workspace *w,
		      struct stray_reduce_sweep_result *res,
		      struct stray_error *err)
{
	size_t v;
	int rc, redo = 0;

	if ((rc = setup(w, err)) || (rc = plan_visits(w, res, err)))
		return rc;
	start_reading(w, res);
	if ((rc = dark_levels(w, res, err)) ||
	    (rc = dark_pixels(w, res, err)) ||
	    (rc = check_visits(w, res, err)) ||
	    (rc = light_buffers(w, res, err)))
		return rc;
	res->drift_in_time = all_timed(w, &res->span_s);
	res->t0_utc = res->drift_in_time ? w->man.e[0].date_obs : 0;
	for (v = 0; v < res->n_visits; v++)
		if ((rc = reduce_visit(w, v, res, err)) != STRAY_OK)
			return rc;
	if (w->o->visits_only)
		return STRAY_OK;	/* merged elsewhere (merge.c) */
	res->points = calloc(res->n_visits, sizeof(*res->points));
	if (!res->points)
		return stray_error_set(err, STRAY_ENOMEM, "curve", "no memory");
	rc = stray_reduce_curve(res->visits, res->n_visits, res->points,
				&res->n_points, &res->drift, err);
	if (rc == STRAY_OK && (rc = add_common(w, res, &redo, err)) ==
	    STRAY_OK && redo)
		rc = stray_reduce_curve(res->visits, res->n_visits,
					res->points, &res->n_points,
					&res->drift, err);
	if (rc == STRAY_OK && to_commanded(w, res))
		rc = stray_reduce_curve(res->visits, res->n_visits,
					res->points, &res->n_points,
					&res->drift, err);
	if (rc != STRAY_OK)
		return stray_error_at(err, rc, w->dir, 0, 0, 0);
	res->p0 = res->drift.p0;
	return track_ghosts(w, res, err);
}

int stray_reduce_sweep(const char *dir, const struct stray_reduce_sweep_opts *o,
		 struct stray_reduce_sweep_result *res, struct stray_error *err)
{
	struct workspace *w = calloc(1, sizeof(*w));
	int rc;

	memset(res, 0, sizeof(*res));
	if (!w)
		return stray_error_set(err, STRAY_ENOMEM, "sweep", "no memory");
	w->dir = dir;
	w->o = o;
	w->monitor = -1;
	/* the loader refuses duplicate rows, with their line */
	rc = stray_sweep_manifest_load(dir, &w->man, err);
	if (rc == STRAY_OK) {
		res->n_frames = w->man.n;
		rc = reduce_all(w, res, err);
		res->n_rows = w->geo.n_rows;
		res->n_cols = w->geo.n_cols;
		res->col0 = w->geo.col0;
	}
	stray_prefetch_stop(&w->pf);
	res->workspace_bytes = w->peak_bytes;
	stray_big_free(w->pix, w->n_pix * sizeof(*w->pix));
	stray_big_free(w->mask, w->n_pix);
	stray_big_free(w->arena, w->arena_bytes);
	free(w->prof_var);
	free(w->ghost_scratch);
	free(w->plan);
	stray_sweep_buf_free(&w->file);
	stray_sweep_manifest_free(&w->man);
	free(w);
	return rc;
}

void stray_reduce_sweep_result_free(struct stray_reduce_sweep_result *res)
{
	size_t i;

	free(res->points);
	free(res->visits);
	free(res->profiles);
	free(res->image);
	for (i = 0; i < STRAY_REDUCE_TRACKS_MAX; i++)
		free(res->tracks[i].pt);
	memset(res, 0, sizeof(*res));
}
