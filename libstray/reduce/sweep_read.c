/*
 * sweep_read.c - the workspace of stray_reduce_sweep (sweep.c) and its
 * frames: one arena on 2 MiB pages, each frame file read once and
 * checked against the first frame's geometry, the next ones read and
 * hashed ahead by the prefetch thread.
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
void *stray_rs_ws_take(struct workspace *w, size_t bytes, size_t at)
{
	w->bytes += bytes;
	if (w->bytes > w->peak_bytes)
		w->peak_bytes = w->bytes;
	return w->arena + at;
}

void stray_rs_ws_give(struct workspace *w, size_t bytes)
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
int stray_rs_load_frame(struct workspace *w, const struct stray_sweep_entry *e,
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
int stray_rs_at_frame(struct workspace *w, const struct stray_sweep_entry *e,
		      int rc, struct stray_error *err)
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
int stray_rs_setup(struct workspace *w, struct stray_error *err)
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

/*
 * The order load_frame will ask for frames in: the darks (pass 1), the
 * darks pass 1 could not keep (pass 2), then every visit's light frames.
 * Without memory for the list the frames are read as asked.
 */
void stray_rs_start_reading(struct workspace *w,
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
