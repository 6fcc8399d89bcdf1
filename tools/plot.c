/*
 * plot.c - PNG line plots through PLplot's pngcairo device.
 */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "plot.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define PLOT_W_PX 1100
#define PLOT_H_PX 720
#define SERIES_MAX 16

/* White background, then the colours of enum plot_color. */
static const PLINT pal_r[] = { 255, 0, 31, 214, 44, 255, 127, 148 };
static const PLINT pal_g[] = { 255, 0, 119, 39, 160, 127, 127, 103 };
static const PLINT pal_b[] = { 255, 0, 180, 40, 44, 14, 127, 189 };

static double axis_value(double v, int log_axis)
{
	if (!log_axis)
		return v;
	return v > 0.0 ? log10(v) : NAN;
}

/* Data range of all series along one axis (after the log transform). */
static void data_range(const struct plot_spec *p, int y, double *lo,
		       double *hi)
{
	size_t s, i;

	*lo = INFINITY;
	*hi = -INFINITY;
	for (s = 0; s < p->n_series; s++)
		for (i = 0; i < p->series[s].n; i++) {
			double v = axis_value(y ? p->series[s].y[i]
						: p->series[s].x[i],
					      y ? p->log_y : p->log_x);

			if (isfinite(v)) {
				*lo = fmin(*lo, v);
				*hi = fmax(*hi, v);
			}
		}
	if (!isfinite(*lo)) {
		*lo = 0.0;
		*hi = 1.0;
	}
	if (*hi - *lo < 1e-12) {
		*lo -= 0.5;
		*hi += 0.5;
	}
}

static void axis_limits(const struct plot_spec *p, int y, double *lo,
			double *hi)
{
	double dmin, dmax, want_lo = y ? p->y_min : p->x_min,
			   want_hi = y ? p->y_max : p->x_max;
	int log_axis = y ? p->log_y : p->log_x;

	data_range(p, y, &dmin, &dmax);
	*lo = isnan(want_lo) ? dmin : axis_value(want_lo, log_axis);
	*hi = isnan(want_hi) ? dmax : axis_value(want_hi, log_axis);
	if (isnan(want_lo) && isnan(want_hi) && !log_axis) {
		double pad = 0.03 * (*hi - *lo);

		*lo -= pad;
		*hi += pad;
	}
}

/* Draw runs of consecutive finite points as one polyline each. */
static void draw_series(const struct plot_spec *p,
			const struct plot_series *s, PLFLT *x, PLFLT *y)
{
	size_t i, run = 0;

	plcol0(s->color);
	pllsty(s->style == PLOT_DASHED ? 3 : s->style == PLOT_DOTTED ? 2 : 1);
	for (i = 0; i <= s->n; i++) {
		double xv = i < s->n ? axis_value(s->x[i], p->log_x) : NAN;
		double yv = i < s->n ? axis_value(s->y[i], p->log_y) : NAN;

		if (isfinite(xv) && isfinite(yv)) {
			x[run] = xv;
			y[run++] = yv;
			continue;
		}
		if (run > 0 && s->style == PLOT_POINTS)
			plstring((PLINT)run, x, y, "#(728)");
		else if (run > 1)
			plline((PLINT)run, x, y);
		run = 0;
	}
	pllsty(1);
}

static void draw_error_bars(const struct plot_spec *p,
			    const struct plot_series *s, PLFLT *x, PLFLT *lo,
			    PLFLT *hi)
{
	size_t i, k = 0;

	for (i = 0; i < s->n; i++) {
		double xv = axis_value(s->x[i], p->log_x);
		double l = axis_value(s->y_lo[i], p->log_y);
		double h = axis_value(s->y_hi[i], p->log_y);

		if (p->log_y && !isfinite(l) && isfinite(h))
			l = -300.0;	/* bar reaches zero: down to the axis */
		if (!isfinite(xv) || !isfinite(l) || !isfinite(h))
			continue;
		x[k] = xv;
		lo[k] = l;
		hi[k++] = h;
	}
	plcol0(s->color);
	if (k > 0)
		plerry((PLINT)k, x, lo, hi);
}

static void draw_legend(const struct plot_spec *p)
{
	PLINT opt[SERIES_MAX], tcol[SERIES_MAX], lcol[SERIES_MAX],
	      lsty[SERIES_MAX], scol[SERIES_MAX], snum[SERIES_MAX];
	PLFLT lw[SERIES_MAX], ssc[SERIES_MAX], w, h;
	const char *text[SERIES_MAX], *sym[SERIES_MAX];
	size_t s;
	PLINT n = 0;

	for (s = 0; s < p->n_series && n < SERIES_MAX; s++) {
		const struct plot_series *ps = &p->series[s];

		if (!ps->label)
			continue;
		opt[n] = ps->style == PLOT_POINTS ? PL_LEGEND_SYMBOL
						  : PL_LEGEND_LINE;
		tcol[n] = PLOT_BLACK;
		lcol[n] = scol[n] = ps->color;
		lsty[n] = ps->style == PLOT_DASHED ? 3 : ps->style == PLOT_DOTTED ? 2 : 1;
		lw[n] = 1.5;
		ssc[n] = 1.0;
		snum[n] = 1;
		sym[n] = "#(728)";
		text[n++] = ps->label;
	}
	if (n == 0)
		return;
	pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
		 (p->legend_bottom ? PL_POSITION_BOTTOM : PL_POSITION_TOP) |
		 PL_POSITION_RIGHT | PL_POSITION_INSIDE,
		 0.02, 0.02, 0.08, 0, PLOT_BLACK, 1, 0, 0, n, opt, 1.0, 0.8,
		 2.0, 0.0, tcol, text, NULL, NULL, NULL, NULL, lcol, lsty, lw,
		 scol, ssc, snum, sym);
}

/* Viewport, grey grid, then the black frame with ticks and labels. */
static void draw_frame(const struct plot_spec *p, double x0, double x1,
		       double y0, double y1)
{
	char xopt[16], yopt[16];

	snprintf(xopt, sizeof(xopt), "bcnst%s", p->log_x ? "l" : "");
	snprintf(yopt, sizeof(yopt), "bcnstv%s", p->log_y ? "l" : "");
	plcol0(PLOT_BLACK);
	plenv(x0, x1, y0, y1, 0, -2);	/* viewport and window only */
	plcol0(PLOT_GREY);
	pllsty(2);
	plbox(p->log_x ? "gl" : "g", 0.0, 0, p->log_y ? "gl" : "g", 0.0, 0);
	pllsty(1);
	plcol0(PLOT_BLACK);
	plbox(xopt, 0.0, 0, yopt, 0.0, 0);
	pllab(p->xlabel, p->ylabel, p->title);
}

/*
 * The PNG goes through the one atomic path (stray/file.h): the temporary
 * is created here (PLplot itself would only print and carry on when it
 * cannot), PLplot writes into it by name, and the commit renames it.
 */
static int open_png(const char *path, struct stray_file_out *out,
		    struct stray_error *err)
{
	/* the library's reason stands ("is also an input of this run",
	 * "Permission denied"), not a vaguer one of ours */
	return stray_file_open_atomic(out, path, err);
}

/*
 * A device or a pipe (/dev/stdout, /dev/full) is written in place, and
 * PLplot would write it by name and ignore a failed write: the figure is
 * drawn into a private temporary and copied through out->f, whose commit
 * reports the errno ("No space left on device").  *scratch gets the
 * temporary's name ("" when none is needed).
 */
static int device_scratch(struct stray_file_out *out, char *scratch,
			  size_t size, struct stray_error *err)
{
	int fd;

	scratch[0] = '\0';
	if (out->tmp[0])
		return STRAY_OK;
	snprintf(scratch, size, "/tmp/stray_plot_XXXXXX");
	if ((fd = mkstemp(scratch)) < 0) {
		scratch[0] = '\0';
		return stray_error_at(err, STRAY_EIO, out->path, 0, "plot",
				      "cannot create a temporary file");
	}
	close(fd);
	return STRAY_OK;
}

static int copy_scratch(const char *scratch, struct stray_file_out *out,
			struct stray_error *err)
{
	FILE *f = fopen(scratch, "rb");
	char buf[65536];
	size_t n;

	if (!f)
		return stray_error_at(err, STRAY_EIO, out->path, 0, "plot",
				      "PLplot wrote no file");
	while ((n = fread(buf, 1, sizeof(buf), f)) > 0)
		if (fwrite(buf, 1, n, out->f) != n)
			break;	/* the commit reports errno */
	fclose(f);
	return STRAY_OK;
}

int plot_render(const struct plot_spec *p, struct stray_error *err)
{
	size_t s, nmax = 1;
	double x0, x1, y0, y1;
	PLFLT *bx, *by, *bz;
	char geom[32];
	struct stray_file_out out;
	char scratch[64];
	int rc = open_png(p->path, &out, err);

	if (rc != STRAY_OK)
		return rc;
	if ((rc = device_scratch(&out, scratch, sizeof(scratch), err))) {
		stray_file_abort(&out);
		return rc;
	}
	for (s = 0; s < p->n_series; s++)
		nmax = p->series[s].n > nmax ? p->series[s].n : nmax;
	bx = malloc(nmax * sizeof(PLFLT));
	by = malloc(nmax * sizeof(PLFLT));
	bz = malloc(nmax * sizeof(PLFLT));
	if (!bx || !by || !bz) {
		rc = stray_error_set(err, STRAY_ENOMEM, "plot", 0);
		goto out_free;
	}
	axis_limits(p, 0, &x0, &x1);
	axis_limits(p, 1, &y0, &y1);
	snprintf(geom, sizeof(geom), "%dx%d", PLOT_W_PX, PLOT_H_PX);
	plsdev("pngcairo");
	plsfnam(out.tmp[0] ? out.tmp : scratch);
	plsetopt("geometry", geom);
	plscmap0(pal_r, pal_g, pal_b, (PLINT)(sizeof(pal_r) / sizeof(pal_r[0])));
	plinit();
	plschr(0.0, 1.1);
	draw_frame(p, x0, x1, y0, y1);
	for (s = 0; s < p->n_series; s++) {
		if (p->series[s].y_lo && p->series[s].y_hi)
			draw_error_bars(p, &p->series[s], bx, by, bz);
		draw_series(p, &p->series[s], bx, by);
	}
	draw_legend(p);
	plend();
	{
		struct stat st;

		if (out.tmp[0] && (stat(out.tmp, &st) != 0 || st.st_size == 0))
			rc = stray_error_at(err, STRAY_EIO, p->path, 0, "plot",
					    "PLplot wrote no file");
	}
	if (rc == STRAY_OK && scratch[0])
		rc = copy_scratch(scratch, &out, err);
	if (rc == STRAY_OK)
		rc = stray_file_commit(&out, err);
out_free:
	if (scratch[0])
		unlink(scratch);
	if (rc != STRAY_OK)
		stray_file_abort(&out);
	free(bx);
	free(by);
	free(bz);
	return rc;
}
