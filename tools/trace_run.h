/*
 * trace_run.h - what `stray trace` and `stray sweep` share about their
 * traces: the tracer options and their defaults.  Who runs the traces is
 * the caller's runner (tracer/runner.h), passed to the command.
 */
#ifndef STRAY_TOOLS_TRACE_RUN_H
#define STRAY_TOOLS_TRACE_RUN_H

#include "tracer/integrator.h"

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
