/*
 * batches.h - a trace cut into pieces for a distributed run (mpi/).
 *
 * tracer_trace() is a pilot pass that builds the guide, then the main
 * pass; each pass is a fixed set of batches whose paths use per-path
 * random streams.  A batch's tallies at angle j depend only on the seed,
 * the path count, the batch count, the guide and theta_j (every angle's
 * next-event connection is independent of the others), so a piece -
 * some batches of a pass, at a subset of the angles - computes exactly
 * the numbers the whole trace computes for it.  Put the pieces' rows
 * into one result and the statistics (result.c, summed in batch order)
 * are bit-identical to tracer_trace() with the same options.
 */
#ifndef TRACER_BATCHES_H
#define TRACER_BATCHES_H

#include "tracer/guide.h"
#include "tracer/integrator.h"

#define TRACER_PILOT_BATCHES 8

/* The checks tracer_trace() makes of scene and options. */
int tracer_trace_check(const struct tracer_scene *s,
		       const struct tracer_trace_opts *o,
		       struct stray_error *err);

/* 1 when tracer_trace(o) runs a pilot to build a guide. */
int tracer_pilot_wanted(const struct tracer_trace_opts *o);

/* The pilot pass's options derived from the trace's. */
void tracer_pilot_opts(const struct tracer_trace_opts *o,
		       struct tracer_trace_opts *po);

/*
 * Batches [first_batch, first_batch + n_batches) of the pass o (o->theta_deg
 * may be a subset of the sweep's angles); res is allocated with all
 * o->n_batches rows, the others left zero.  guide: the main pass's guide,
 * or NULL (pilot pass, or unguided).  pilot_s2: NULL, or for the pilot
 * pass [o->n_batches][TRACER_GUIDE_CELLS][o->n_theta] zeroed by the
 * caller.  With o->record_paths, res->paths holds those batches' path
 * records merged in batch order (one batch: its own sums).  No dumps or
 * maps.
 */
int tracer_trace_batches(const struct tracer_scene *s,
			 const struct tracer_trace_opts *o,
			 const struct tracer_guide *guide, int first_batch,
			 int n_batches, double *pilot_s2,
			 struct tracer_result *res, struct stray_error *err);

/*
 * Strategy B (light-side single scatter, opts.light_paths; tracer/light.h)
 * in pieces: the pilot pass also scores B at every angle, light_pilot
 * [o->n_batches][o->n_theta][TRACER_LIGHT_STATS] zeroed by the caller
 * (NULL: not scored; the main pass: NULL), otherwise as
 * tracer_trace_batches.  tracer_light_alloc() turns the complete pilot
 * (all angles, rows merged in batch order) into the main pass's
 * opts.light_ratio[n_theta]; a piece at angles [j0, j0 + n) passes
 * light_ratio + j0, as theta_deg + j0.  The pieces are then bit-identical
 * to tracer_trace() with light_paths (tests/tracer/test_light_paths.c).
 */
#define TRACER_LIGHT_STATS 19
int tracer_trace_batches_light(const struct tracer_scene *s,
			       const struct tracer_trace_opts *o,
			       const struct tracer_guide *guide,
			       int first_batch, int n_batches,
			       double *pilot_s2, double *light_pilot,
			       struct tracer_result *res,
			       struct stray_error *err);
void tracer_light_alloc(const struct tracer_result *pilot,
			const double *light_pilot, double *ratio);

/*
 * The main pass's guide from a complete pilot result over all angles and
 * its s2 tallies (layout as above), merged in batch order; STRAY_ENOMEM.
 */
int tracer_guide_from_pilot(struct tracer_guide *g,
			    const struct tracer_result *pilot,
			    const double *s2);

#endif /* TRACER_BATCHES_H */
