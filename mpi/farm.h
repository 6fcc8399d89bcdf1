/*
 * farm.h - a master/worker task farm over MPI for the tracer.
 *
 * Rank 0 runs the command; each trace it asks for is cut into pieces
 * (piece.h: angle chunk x batch) that are handed out one or two at a time
 * to whichever rank is free (dynamic load balancing: high-angle chunks
 * and slow ranks simply take fewer), while a thread on rank 0 works
 * through the same queue.  The results land in their own rows, so the
 * merged statistics sum batches in batch order, never arrival order: the
 * output is bit-identical to a one-process run with the same seed.
 * Only rank 0 calls MPI (MPI_THREAD_FUNNELED).
 */
#ifndef STRAY_MPI_FARM_H
#define STRAY_MPI_FARM_H

#include <stdint.h>

#include "tracer/runner.h"

struct farm_config {
	int angle_chunks;	/* angle chunks per batch; 0: automatic */
	double task_timeout_s;	/* silence from a busy rank that is fatal */
	/* path records may be farmed: the caller reads them in an order of
	 * its own (diagnose sorts them), not the table's slot order */
	int paths_any_order;
};

extern struct farm_config farm_config;

/* What the last trace (or set) sent and received, for `make bench`. */
struct farm_stats {
	uint64_t tasks, pilot_tasks;	/* main pass, pilot pass */
	uint64_t task_bytes;	/* main pass: piece and result messages */
	uint64_t pilot_bytes;	/* pilot pass: the same (results carry s2) */
	uint64_t job_bytes;	/* job descriptions and guides */
	uint64_t remote_tasks;	/* main-pass pieces done by other ranks */
	uint64_t remote_pilot;	/* pilot pieces done by other ranks */
	uint64_t scene_builds;	/* scenes built by other ranks (jobs sent) */
	uint64_t local_builds;	/* scenes built by rank 0's own thread */
	double done_s;		/* rank 0: in the caller's per-trace work */
	double local_build_s;	/* rank 0's thread: building scenes */
	double start_s;		/* rank 0: a set's checks before farming */
};

extern struct farm_stats farm_last;

/* Rank 0: a trace over the ranks (stray-mpi's runner, stray_mpi.c). */
int farm_trace(const struct tracer_scene_spec *spec,
	       const struct tracer_scene *s,
	       const struct tracer_trace_opts *o, struct tracer_result *res,
	       struct stray_error *err);

/* Rank 0: n traces at once (a sweep's designs; the runner's run_set):
 * one queue of pieces across them, each trace's main pass waiting only
 * for its own pilot; done(user, i, ...) on this thread as each finishes,
 * while the ranks go on.  No path records, dumps or maps. */
int farm_trace_set(const struct tracer_trace_item *items, size_t n,
		   tracer_item_done_fn done, void *user,
		   struct stray_error *err);

/* Rank 0: 1 once a rank was lost or failed (the job must be aborted). */
int farm_broken(void);

/* Rank 0: let the other ranks return from farm_serve. */
void farm_quit(void);

/* Ranks > 0: serve jobs and pieces until rank 0 says quit; 0 or 1. */
int farm_serve(void);

#endif /* STRAY_MPI_FARM_H */
