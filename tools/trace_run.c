/*
 * trace_run.c - the default trace: this process's threads (trace_run.h).
 */
#include "trace_run.h"

static int trace_local(const struct trace_scene_spec *spec,
		       const struct tracer_scene *s,
		       const struct tracer_trace_opts *o,
		       struct tracer_result *res, struct stray_error *err)
{
	(void)spec;
	return tracer_trace(s, o, res, err);
}

trace_run_fn trace_run = trace_local;
