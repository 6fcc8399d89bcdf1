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
	/* edits after loading that no --set says (stray diagnose's causes),
	 * made by trace_scene_edit before the commit; 0: none */
	double beam_shift_z;	/* beam centre moved by -this along z, m */
	double abg_g;		/* > 0: Lambertian groups become ABg, this g */
};

/* spec's edits to a loaded, not yet committed scene. */
void trace_scene_edit(const struct trace_scene_spec *spec,
		      struct tracer_scene *s);

typedef int (*trace_run_fn)(const struct trace_scene_spec *spec,
			    const struct tracer_scene *s,
			    const struct tracer_trace_opts *o,
			    struct tracer_result *res,
			    struct stray_error *err);

extern trace_run_fn trace_run;

/* The tracer options `stray trace` and `stray sweep` share. */
#define TRACE_RUN_LONG_OPTIONS \
	{ "rays", required_argument, NULL, 'n' }, \
	{ "seed", required_argument, NULL, 'k' }, \
	{ "threads", required_argument, NULL, 't' }, \
	{ "batches", required_argument, NULL, 'b' }

/* Tracer defaults with n_paths paths on every online CPU. */
void trace_run_defaults(struct tracer_trace_opts *o, uint64_t n_paths);

/*
 * Take one of TRACE_RUN_LONG_OPTIONS into o: 0 when opt was one of them
 * (*rc then says whether its value was good), 1 otherwise.
 */
int trace_run_option(const char *cmd, int opt, const char *text,
		     struct tracer_trace_opts *o, int *rc);

#endif /* STRAY_TOOLS_TRACE_RUN_H */
