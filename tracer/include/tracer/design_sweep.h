/*
 * design_sweep.h - `stray sweep` as one call: every design of a grid
 * (tracer/design_grid.h) traced through the caller's runner, each
 * finished design's curve kept in a state folder (design_NNNN.csv, taken
 * back when the same run asks again), and judged against an alpha_req:
 * its Sun exclusion angle (thesis §5.1, fig. 5.1) with the interval from
 * alpha -/+ sigma, and alpha at the chosen angles.  The command
 * (tools/cmd_sweep.c) tables, plots and prints the results.
 */
#ifndef STRAY_TRACER_DESIGN_SWEEP_H
#define STRAY_TRACER_DESIGN_SWEEP_H

#include <stddef.h>

#include "stray/error.h"
#include "tracer/design_grid.h"
#include "tracer/detector.h"
#include "tracer/integrator.h"
#include "tracer/runner.h"

#define SWEEP_AT_MAX 16

struct design_result {
	char label[GRID_AXES_MAX * 2 * GRID_TEXT_MAX];
	double sun_deg, sun_lo_deg, sun_hi_deg;	/* NaN: not excluded */
	double alpha_at[SWEEP_AT_MAX];
	int resumed;			/* read back from the state folder */
};

#define DESIGN_SWEEP_SETS_MAX 64

struct design_sweep {
	/* inputs */
	const struct tracer_runner *runner;	/* who runs the traces */
	const char *scene;	/* 'ref4' or a scene file */
	const char *angles;	/* angle list; NULL: 0:30:5,30:90:1 */
	const char *at_list;	/* alpha reported at; NULL: 20,30,40 */
	const char *lens;	/* a lens curve; NULL: none */
	const char *state;	/* the folder of kept curves (created) */
	const char *sets[DESIGN_SWEEP_SETS_MAX];	/* fixed --set */
	int n_sets;
	struct design_grid grid;
	struct tracer_trace_opts o;
	/* called after each design (NULL: not) */
	void (*progress)(void *user, size_t i, size_t n,
			 const struct design_result *d);
	void *progress_user;
	/* filled by design_sweep_run */
	double at[SWEEP_AT_MAX];
	int n_at;
	struct design_result *d;	/* grid.n_designs of them */
	double *theta;		/* the traced angles, 0 first */
	struct tracer_lens lens_model;
};

/* Trace or take back every design of the grid and judge it against
 * alpha_req; an error naming the option (--grid for a grid axis the
 * scene refuses) and value.  Free with design_sweep_free. */
int design_sweep_run(struct design_sweep *w, double alpha_req,
		     struct stray_error *err);

void design_sweep_free(struct design_sweep *w);

#endif /* STRAY_TRACER_DESIGN_SWEEP_H */
