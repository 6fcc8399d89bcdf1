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

struct tracer_runner {
	tracer_run_fn run;
	void *ctx;		/* the runner's own, passed to run */
};

/* tracer_trace() in this process. */
extern const struct tracer_runner tracer_runner_local;

/* r->run(r->ctx, ...). */
int tracer_run(const struct tracer_runner *r,
	       const struct tracer_scene_spec *spec,
	       const struct tracer_scene *s, const struct tracer_trace_opts *o,
	       struct tracer_result *res, struct stray_error *err);

#endif /* TRACER_RUNNER_H */
