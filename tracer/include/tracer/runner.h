/*
 * runner.h - who carries out a trace: a function and its context, passed
 * by the caller to every command and library that traces (`stray trace`,
 * `stray sweep`, the diagnosis's trace cache).  `stray` passes
 * tracer_runner_local (this process's threads); `stray-mpi` passes its
 * MPI task farm, which also needs the scene's description so that the
 * other ranks can build the same scene.  A runner is const: nothing
 * swaps it behind a caller's back.
 */
#ifndef TRACER_RUNNER_H
#define TRACER_RUNNER_H

#include "stray/error.h"
#include "tracer/integrator.h"
#include "tracer/scene.h"

/* How to rebuild a scene elsewhere: tracer_scene_load's arguments plus
 * the edits made after loading. */
struct tracer_scene_spec {
	const char *scene;		/* 'ref4' or a scene file */
	const char *const *sets;	/* --set key=value overrides */
	int n_sets;
	const char *lens;		/* lens table path, or NULL */
	/* edits after loading that no --set says (the diagnosis's causes),
	 * made by tracer_scene_spec_edit before the commit; 0: none */
	double beam_shift_z;	/* beam centre moved back along its normal, mm */
	double abg_g;		/* > 0: Lambertian groups become ABg, this g */
};

/* spec's edits to a loaded, not yet committed scene. */
void tracer_scene_spec_edit(const struct tracer_scene_spec *spec,
			    struct tracer_scene *s);

/* Trace the committed scene s (built from spec) with options o, as
 * tracer_trace() does: same seed, same bits. */
typedef int (*tracer_run_fn)(void *ctx, const struct tracer_scene_spec *spec,
			     const struct tracer_scene *s,
			     const struct tracer_trace_opts *o,
			     struct tracer_result *res,
			     struct stray_error *err);

/* One trace of a set (a sweep's designs): its scene as a description
 * (built by whoever traces it) and its options. */
struct tracer_trace_item {
	struct tracer_scene_spec spec;
	const struct tracer_trace_opts *o;
};

/* Called on the caller's thread as each trace of a set is finished:
 * res is item i's, freed after the call.  Nonzero (err set): the set
 * stops with that error. */
typedef int (*tracer_item_done_fn)(void *user, size_t i,
				   const struct tracer_result *res,
				   struct stray_error *err);

/* Run n traces, in any order and at once if the runner can (the MPI
 * farm keeps every rank busy across a sweep's designs): each item's
 * result the bits tracer_trace() gives it. */
typedef int (*tracer_run_set_fn)(void *ctx,
				 const struct tracer_trace_item *items,
				 size_t n, tracer_item_done_fn done,
				 void *user, struct stray_error *err);

struct tracer_runner {
	tracer_run_fn run;
	void *ctx;		/* the runner's own, passed to run */
	/* NULL: one trace after another, in index order, each scene built
	 * here and traced through run */
	tracer_run_set_fn run_set;
};

/* tracer_trace() in this process. */
extern const struct tracer_runner tracer_runner_local;

/* r->run(r->ctx, ...). */
int tracer_run(const struct tracer_runner *r,
	       const struct tracer_scene_spec *spec,
	       const struct tracer_scene *s, const struct tracer_trace_opts *o,
	       struct tracer_result *res, struct stray_error *err);

/* r->run_set, or the items one after another through r->run. */
int tracer_run_set(const struct tracer_runner *r,
		   const struct tracer_trace_item *items, size_t n,
		   tracer_item_done_fn done, void *user,
		   struct stray_error *err);

#endif /* TRACER_RUNNER_H */
