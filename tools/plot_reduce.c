/*
 * plot_reduce.c - the figures of `stray reduce --plot-dir`: alpha_lens with
 * its noise floor (thesis fig. 3.7), row-collapsed profiles over angle
 * (fig. 3.9), the ghost tracks, and false-colour J (fig. 3.8, OpenCV).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "frames/image_cv.h"
#include "plot.h"
#include "reduce_report.h"
#include "stray/errfmt.h"

static int plot_alpha(const char *dir,
		      const struct stray_reduce_sweep_result *r,
		      struct stray_error *err)
{
	size_t n = r->n_points, i;
	double *buf = calloc(5 * (n ? n : 1), sizeof(double));
	double *th = buf, *a = th + n, *lo = a + n, *hi = lo + n, *nf = hi + n;
	struct plot_series s[2] = { { 0 } };
	struct plot_spec p = { 0 };
	char path[4096];
	int rc;

	if (!buf)
		return stray_error_set(err, STRAY_ENOMEM, "plot", "no memory");
	for (i = 0; i < n; i++) {
		th[i] = r->points[i].theta_deg;
		a[i] = r->points[i].alpha;
		lo[i] = a[i] - r->points[i].sigma;
		hi[i] = a[i] + r->points[i].sigma;
		nf[i] = r->points[i].noise_floor;
	}
	s[0] = (struct plot_series){ th, a, n, lo, hi, PLOT_BLUE, PLOT_LINE,
				     "lens attenuation" };
	s[1] = (struct plot_series){ th, nf, n, NULL, NULL, PLOT_RED,
				     PLOT_DASHED, "noise floor" };
	snprintf(path, sizeof(path), "%s/alpha.png", dir);
	p = (struct plot_spec){ path, "Lens attenuation (fig. 3.7)",
		"boresight offset angle theta, deg",
		"normalised attenuation alpha_lens", 0, 1, NAN, NAN, NAN, NAN,
		s, 2, 0 };
	rc = plot_render(&p, err);
	free(buf);
	return rc;
}

/* Profiles / Pbar(0), one line per angle (first visit of each). */
static int plot_profiles(const char *dir,
			 const struct stray_reduce_sweep_result *r,
			 struct stray_error *err)
{
	size_t nc = r->n_cols, nv = r->n_visits, v, c, k = 0;
	double *x = calloc(nc, sizeof(double));
	double *y = calloc(nv * nc, sizeof(double));
	struct plot_series *s = calloc(nv, sizeof(*s));
	double pbar0 = r->p0 / (double)(r->n_rows * nc);
	struct plot_spec p;
	char path[4096];
	int rc;

	if (!x || !y || !s) {
		free(x), free(y), free(s);
		return stray_error_set(err, STRAY_ENOMEM, "plot", "no memory");
	}
	for (c = 0; c < nc; c++)
		x[c] = (double)c + (double)r->col0;
	for (v = 0; v < nv; v++) {
		for (c = 0; c < nc; c++)
			y[v * nc + c] = r->profiles[v * nc + c] / pbar0;
		s[k++] = (struct plot_series){ x, y + v * nc, nc, NULL, NULL,
			(enum plot_color)(PLOT_BLUE + v % 6), PLOT_LINE, NULL };
	}
	snprintf(path, sizeof(path), "%s/profiles.png", dir);
	p = (struct plot_spec){ path, "Row-collapsed J per angle (fig. 3.9)",
		"detector column", "mean J / Pbar(0)", 0, 1, NAN, NAN, NAN,
		NAN, s, k, 0 };
	rc = plot_render(&p, err);
	free(x), free(y), free(s);
	return rc;
}

static int plot_tracks(const char *dir,
		       const struct stray_reduce_sweep_result *r,
		       struct stray_error *err)
{
	struct plot_series s[STRAY_REDUCE_TRACKS_MAX];
	double *xy[STRAY_REDUCE_TRACKS_MAX][2] = { { 0 } };
	struct plot_spec p;
	char path[4096];
	size_t i, k;
	int rc = STRAY_OK;

	for (i = 0; i < r->n_tracks && rc == STRAY_OK; i++) {
		const struct stray_ghost_track *t = &r->tracks[i];

		xy[i][0] = calloc(t->n, sizeof(double));
		xy[i][1] = calloc(t->n, sizeof(double));
		if (!xy[i][0] || !xy[i][1]) {
			rc = stray_error_set(err, STRAY_ENOMEM, "plot",
					     "no memory");
			break;
		}
		for (k = 0; k < t->n; k++) {
			xy[i][0][k] = t->pt[k].theta_deg;
			xy[i][1][k] = t->pt[k].column + (double)r->col0;
		}
		s[i] = (struct plot_series){ xy[i][0], xy[i][1], t->n, NULL,
			NULL, (enum plot_color)(PLOT_BLUE + i % 6), PLOT_POINTS,
			reduce_track_name(i) };
	}
	snprintf(path, sizeof(path), "%s/ghosts.png", dir);
	p = (struct plot_spec){ path, "Ghost tracks", "theta, deg",
		"detector column", 0, 0, NAN, NAN, (double)r->col0,
		(double)r->col0 + (double)r->n_cols, s, r->n_tracks, 0 };
	if (rc == STRAY_OK && r->n_tracks > 0)
		rc = plot_render(&p, err);
	for (i = 0; i < STRAY_REDUCE_TRACKS_MAX; i++)
		free(xy[i][0]), free(xy[i][1]);
	return rc;
}

int reduce_plots(const char *dir, const struct stray_reduce_sweep_result *r,
		 struct stray_error *err)
{
	char path[4096], msg[256];
	int rc;

	if ((rc = plot_alpha(dir, r, err)) || (rc = plot_profiles(dir, r,
								  err)) ||
	    (rc = plot_tracks(dir, r, err)))
		return rc;
	if (!r->image)
		return STRAY_OK;
	snprintf(path, sizeof(path), "%s/j.png", dir);
	if (image_cv_false_colour(path, r->image, r->n_rows, r->n_cols, 1, 512,
				  msg, sizeof(msg)) != 0) {
		stray_error_at(err, STRAY_EIO, path, 0, "image",
			       "cannot write");
		stray_error_text(err, msg);
		return STRAY_EIO;
	}
	return STRAY_OK;
}
