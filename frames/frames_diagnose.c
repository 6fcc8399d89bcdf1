/*
 * frames_diagnose.c - when measured false stars disagree with the model,
 * name what the frames show (frames_run.h): the analysis sees only the
 * frames' background tiles and the false stars' positions.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frames/frames_run.h"

struct plane { double a, bx, by, sig_bx, sig_by; };

/* Least-squares plane T = a + bx x + by y over tile centres, x and y in
 * [-1, 1] across the frame; slope sigmas from the fit residuals. */
static void fit_plane(const struct frames_evidence *ev, int tile_px,
		      int cols, int rows, struct plane *p)
{
	double sx2 = 0, sy2 = 0, st = 0, sxt = 0, syt = 0, mx = 0, my = 0;
	double res2 = 0;
	int i, j, n = ev->tiles_x * ev->tiles_y;

	for (j = 0; j < ev->tiles_y; j++)
		for (i = 0; i < ev->tiles_x; i++) {
			mx += 2.0 * ((i + 0.5) * tile_px) / cols - 1.0;
			my += 2.0 * ((j + 0.5) * tile_px) / rows - 1.0;
		}
	mx /= n;
	my /= n;
	for (j = 0; j < ev->tiles_y; j++)
		for (i = 0; i < ev->tiles_x; i++) {
			double x = 2.0 * ((i + 0.5) * tile_px) / cols - 1.0 - mx;
			double y = 2.0 * ((j + 0.5) * tile_px) / rows - 1.0 - my;
			double t = ev->tile_sum[j * ev->tiles_x + i] / ev->frames;

			sx2 += x * x; sy2 += y * y; st += t;
			sxt += x * t; syt += y * t;
		}
	p->a = st / n;
	p->bx = sx2 > 0 ? sxt / sx2 : 0;
	p->by = sy2 > 0 ? syt / sy2 : 0;
	for (j = 0; j < ev->tiles_y; j++)
		for (i = 0; i < ev->tiles_x; i++) {
			double x = 2.0 * ((i + 0.5) * tile_px) / cols - 1.0 - mx;
			double y = 2.0 * ((j + 0.5) * tile_px) / rows - 1.0 - my;
			double d = ev->tile_sum[j * ev->tiles_x + i] / ev->frames -
				   (p->a + p->bx * x + p->by * y);
			res2 += d * d;
		}
	res2 = n > 3 ? res2 / (n - 3) : 0;
	p->sig_bx = sx2 > 0 ? sqrt(res2 / sx2) : 0;
	p->sig_by = sy2 > 0 ? sqrt(res2 / sy2) : 0;
}

static int cmp_pos(const void *a, const void *b)
{
	const long *x = a, *y = b;

	return (*x > *y) - (*x < *y);
}

/* Places (whole pixels) where false stars recur in >= 3 frames. */
static int recurring_places(const struct frames_evidence *ev)
{
	long *key = malloc((ev->n_f + 1) * sizeof(*key));
	size_t i, run = 1;
	int places = 0;

	if (!key)
		return 0;
	for (i = 0; i < ev->n_f; i++)
		key[i] = (long)floor(ev->fy[i]) * 100000L + (long)floor(ev->fx[i]);
	qsort(key, ev->n_f, sizeof(*key), cmp_pos);
	for (i = 1; i <= ev->n_f; i++) {
		if (i < ev->n_f && key[i] == key[i - 1]) {
			run++;
			continue;
		}
		places += run >= 3;
		run = 1;
	}
	free(key);
	return places;
}

int frames_diagnose(const struct frames_model *fm,
		    const struct frames_evidence *ev, double measured,
		    double model, int tile_px, char *text, size_t size)
{
	double e = model * ev->frames, n = measured * ev->frames;
	double ratio = model > 0 ? measured / model : INFINITY;
	double level = fm->stray_e + fm->dark_e;
	struct plane p;
	int hot, off, k = 0;

	off = fabs(n - e) > 3.0 * sqrt(e) + 3.0 &&
	      (ratio > 1.5 || ratio < 1.0 / 1.5);
	k += snprintf(text + k, size - k,
		      "%s: measured %.3g false stars per frame, model %.3g (ratio %.3g)",
		      off ? "model and frames disagree" :
		      "model and frames agree within the counts' noise",
		      measured, model, ratio);
	if (!off || ev->frames < 1)
		return 0;
	fit_plane(ev, tile_px, fm->cols, fm->rows, &p);
	hot = ev->frames >= 3 ? recurring_places(ev) : 0;
	if (fabs(p.bx) > 5.0 * p.sig_bx && fabs(p.bx) > 0.02 * p.a)
		k += snprintf(text + k, size - k,
			      "; cause: stray-light gradient along columns, %+.1f %% centre to edge (the model assumes uniform light, thesis §2.3)",
			      100.0 * p.bx / p.a);
	else if (fabs(p.by) > 5.0 * p.sig_by && fabs(p.by) > 0.02 * p.a)
		k += snprintf(text + k, size - k,
			      "; cause: stray-light gradient along rows, %+.1f %% centre to edge (the model assumes uniform light, thesis §2.3)",
			      100.0 * p.by / p.a);
	else if (hot > 0)
		k += snprintf(text + k, size - k,
			      "; cause: hot pixels, %d fixed places give false stars in 3 or more frames (not in the model)",
			      hot);
	else if (fabs(p.a / level - 1.0) > 0.02)
		k += snprintf(text + k, size - k,
			      "; cause: background %.4g e-/px against the model's %.4g (alpha, k_px or the flux is off)",
			      p.a, level);
	else
		k += snprintf(text + k, size - k,
			      "; cause: not in the background or positions (detector or noise model)");
	return 1;
}
