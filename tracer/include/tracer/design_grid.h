/*
 * design_grid.h - the design grid of `stray sweep`: --grid key=v1,v2,...
 * axes over baffle parameters, their Cartesian product (the last axis
 * varies fastest), and each design's --set list and label.
 */
#ifndef STRAY_TRACER_DESIGN_GRID_H
#define STRAY_TRACER_DESIGN_GRID_H

#include <stddef.h>

#include "stray/error.h"

#define GRID_AXES_MAX 8
#define GRID_VALUES_MAX 32
#define GRID_TEXT_MAX 128

struct grid_axis {
	char key[GRID_TEXT_MAX];
	char value[GRID_VALUES_MAX][GRID_TEXT_MAX];
	int n;
};

struct design_grid {
	struct grid_axis axis[GRID_AXES_MAX];
	int n_axes;
	size_t n_designs;	/* product of the axes' lengths */
};

/* Add an axis from "key=v1,v2,..."; STRAY_EINVAL naming the text. */
int design_grid_add(struct design_grid *g, const char *text,
		    struct stray_error *err);

/* Design d's "key=value" settings (set[axis], each GRID_TEXT_MAX * 2). */
void design_grid_sets(const struct design_grid *g, size_t d,
		      char set[][2 * GRID_TEXT_MAX]);

/* "key=value key=value ..." of design d. */
void design_grid_label(const struct design_grid *g, size_t d, char *buf,
		       size_t size);

#endif /* STRAY_TRACER_DESIGN_GRID_H */
