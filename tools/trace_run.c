/*
 * trace_run.c - the tracer options `stray trace` and `stray sweep` share
 * (trace_run.h).
 */
#include <unistd.h>

#include "cli.h"
#include "trace_run.h"

void trace_run_defaults(struct tracer_trace_opts *o, uint64_t n_paths)
{
	long ncpu = sysconf(_SC_NPROCESSORS_ONLN);

	tracer_trace_defaults(o);
	o->n_paths = n_paths;
	o->threads = ncpu > 0 && ncpu <= 256 ? (int)ncpu : 1;
}

int trace_run_option(const char *cmd, int opt, const char *text,
		     struct tracer_trace_opts *o, int *rc)
{
	double v = 0.0;

	switch (opt) {
	case 'n': *rc = cli_parse_count(cmd, "rays", text, 2, 1e12, &v);
		o->n_paths = (uint64_t)v; return 0;
	case 'k': *rc = cli_parse_count(cmd, "seed", text, 0, 9e15, &v);
		o->seed = (uint64_t)v; return 0;
	case 't': *rc = cli_parse_count(cmd, "threads", text, 1, 256, &v);
		o->threads = (int)v; return 0;
	case 'b': *rc = cli_parse_count(cmd, "batches", text, 2, 4096, &v);
		o->n_batches = (int)v; return 0;
	default:
		return 1;
	}
}
