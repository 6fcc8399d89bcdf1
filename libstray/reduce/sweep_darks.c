/*
 * sweep_darks.c - the darks of a sweep (thesis §3.2): the levels per read
 * channel, then the hot and dead pixels, in two passes over the dark
 * frames (the first pass's kept in the workspace's arena).
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

/* Pass 1 over the darks: levels per channel and exposure time. */
int stray_rs_dark_levels(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err)
{
	uint32_t *hist = stray_rs_ws_take(w, STRAY_DARK_HIST_LEN * sizeof(*hist),
					  0);
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
		rc = stray_rs_load_frame(w, &w->man.e[i], &f, pix, err);
		if (rc == STRAY_OK)
			rc = stray_rs_at_frame(w, &w->man.e[i],
				      stray_dark_add(&w->dark, &f, hist, err),
				      err);
		if (rc == STRAY_OK && keep)
			w->cached[w->n_cached++] = f;
		res->n_darks++;
	}
	stray_rs_ws_give(w, STRAY_DARK_HIST_LEN * sizeof(*hist));
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
int stray_rs_dark_pixels(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err)
{
	size_t nb = w->n_pix * sizeof(double), i, k = 0;
	double *mean = stray_rs_ws_take(w, nb, 0);
	double *m2 = stray_rs_ws_take(w, nb, nb);
	/* over the cached darks: used once they are done with */
	double *scratch = stray_rs_ws_take(w, nb, 2 * nb);
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
			rc = stray_rs_load_frame(w, &w->man.e[i], &f, w->pix,
						 err);
		if (rc == STRAY_OK)
			rc = stray_rs_at_frame(w, &w->man.e[i],
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
	stray_rs_ws_give(w, 3 * nb);
	return rc;
}
