/*
 * plot.h - line plots to PNG through PLplot (cairo driver).
 *
 * One call renders one figure: series of lines, points or error bars on
 * linear or log axes, with a legend.  Log axes take data in linear units
 * and drop non-positive points.
 */
#ifndef STRAY_TOOLS_PLOT_H
#define STRAY_TOOLS_PLOT_H

#include <stddef.h>

#include "stray/error.h"

enum plot_style { PLOT_LINE, PLOT_DASHED, PLOT_POINTS, PLOT_DOTTED };
enum plot_color {
	PLOT_BLACK = 1, PLOT_BLUE, PLOT_RED, PLOT_GREEN, PLOT_ORANGE,
	PLOT_GREY, PLOT_PURPLE
};

struct plot_series {
	const double *x, *y;
	size_t n;
	const double *y_lo, *y_hi;	/* error bars, or NULL */
	enum plot_color color;
	enum plot_style style;
	const char *label;		/* legend text, or NULL */
};

struct plot_spec {
	const char *path;		/* PNG output */
	const char *title, *xlabel, *ylabel;
	int log_x, log_y;
	double x_min, x_max, y_min, y_max;	/* NaN: from the data */
	const struct plot_series *series;
	size_t n_series;
	int legend_bottom;		/* 1: legend bottom right (default top) */
};

/* Render spec to spec->path; STRAY_EIO when the file cannot be written. */
int plot_render(const struct plot_spec *spec, struct stray_error *err);

#endif /* STRAY_TOOLS_PLOT_H */
