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
#include "sweep_ws.h"

void stray_reduce_sweep_opts_default(struct stray_reduce_sweep_opts *o)
{
	memset(o, 0, sizeof(*o));
	stray_bayer_default(&o->map);
	stray_ghost_opts_default(&o->ghost);
	o->hot_sigma = 6.0;
	o->verify_sha256 = 1;
}

static int reduce_all(struct workspace *w,
		      struct stray_reduce_sweep_result *res,
		      struct stray_error *err)
{
	size_t v;
	int rc, redo = 0;

	if ((rc = stray_rs_setup(w, err)) ||
	    (rc = stray_rs_plan_visits(w, res, err)))
		return rc;
	stray_rs_start_reading(w, res);
	if ((rc = stray_rs_dark_levels(w, res, err)) ||
	    (rc = stray_rs_dark_pixels(w, res, err)) ||
	    (rc = stray_rs_check_visits(w, res, err)) ||
	    (rc = stray_rs_light_buffers(w, res, err)))
		return rc;
	res->drift_in_time = stray_rs_all_timed(w, &res->span_s);
	res->t0_utc = res->drift_in_time ? w->man.e[0].date_obs : 0;
	for (v = 0; v < res->n_visits; v++)
		if ((rc = stray_rs_reduce_visit(w, v, res, err)) != STRAY_OK)
			return rc;
	if (w->o->visits_only)
		return STRAY_OK;	/* merged elsewhere (merge.c) */
	res->points = calloc(res->n_visits, sizeof(*res->points));
	if (!res->points)
		return stray_error_set(err, STRAY_ENOMEM, "curve", "no memory");
	rc = stray_reduce_curve(res->visits, res->n_visits, res->points,
				&res->n_points, &res->drift, err);
	if (rc == STRAY_OK && (rc = stray_rs_add_common(w, res, &redo, err)) ==
	    STRAY_OK && redo)
		rc = stray_reduce_curve(res->visits, res->n_visits,
					res->points, &res->n_points,
					&res->drift, err);
	if (rc == STRAY_OK && stray_rs_to_commanded(w, res))
		rc = stray_reduce_curve(res->visits, res->n_visits,
					res->points, &res->n_points,
					&res->drift, err);
	if (rc != STRAY_OK)
		return stray_error_at(err, rc, w->dir, 0, 0, 0);
	res->p0 = res->drift.p0;
	return stray_rs_track_ghosts(w, res, err);
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
