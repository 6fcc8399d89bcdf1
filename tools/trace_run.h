/*
 * trace_run.h - the one call through which `stray trace` and `stray
 * sweep` run a trace.  `stray` points it at tracer_trace(); `stray-mpi`
 * (mpi/) points it at the MPI task farm, which needs the scene's
 * description too, so that the other ranks can build the same scene.
 */
#ifndef STRAY_TOOLS_TRACE_RUN_H
#define STRAY_TOOLS_TRACE_RUN_H

#include "tracer/integrator.h"

struct trace_scene_spec {
	const char *scene;		/* 'ref4' or a scene file */
	const char *const *sets;	/* --set key=value overrides */
	int n_sets;
	const char *lens;		/* lens table path, or NULL */
};

typedef int (*trace_run_fn)(const struct trace_scene_spec *spec,
			    const struct tracer_scene *s,
			    const struct tracer_trace_opts *o,
			    struct tracer_result *res,
			    struct stray_error *err);

extern trace_run_fn trace_run;

#endif /* STRAY_TOOLS_TRACE_RUN_H */
