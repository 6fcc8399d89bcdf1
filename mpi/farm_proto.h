/*
 * farm_proto.h - private to the farm: message tags, the job description
 * every rank rebuilds its scene from, and the polling wait.
 */
#ifndef STRAY_MPI_FARM_PROTO_H
#define STRAY_MPI_FARM_PROTO_H

#include <stddef.h>
#include <stdint.h>

#include "farm.h"
#include "piece.h"

enum farm_tag {
	TAG_JOB = 1,	/* bytes: farm_job packed (its trace's number) */
	TAG_GUIDE,	/* bytes: struct farm_guide_msg, then (light_paths)
			 * B's n_theta ratios as doubles */
	TAG_TASK,	/* int[5]: trace, then struct piece */
	TAG_RESULT,	/* double[]: the piece's payload (piece.h) */
	TAG_ERROR,	/* char[]: one line from a failed rank */
	TAG_ENDJOB,	/* int: the trace whose scene to drop */
	TAG_QUIT	/* empty */
};

#define FARM_SETS_MAX 64

/* A trace's guide, for the ranks that trace its main pass. */
struct farm_guide_msg {
	int64_t trace;
	struct tracer_guide g;
};

/* A trace as a rank other than 0 needs it; strings point into the buffer. */
struct farm_job {
	int id;			/* the trace's number in its set */
	struct tracer_trace_opts o;
	const char *scene, *lens;	/* lens: NULL when none */
	const char *sets[FARM_SETS_MAX];
	int n_sets;
	double beam_shift_z, abg_g;	/* tracer_scene_spec_edit's */
};

/* Pack spec and o into a new buffer (caller frees); NULL when out of memory. */
char *farm_job_pack(const struct tracer_scene_spec *spec,
		    const struct tracer_trace_opts *o, int id, size_t *len);

/* Unpack into j; its pointers point into buf (kept by the caller);
 * theta_deg too.  STRAY_EINVAL on a malformed buffer. */
int farm_job_unpack(char *buf, size_t len, struct farm_job *j,
		    struct stray_error *err);

/* Monotonic seconds. */
double farm_now(void);

/* Rank 0's sleep between polls: long enough to leave the core to its
 * own tracing thread (the other ranks block in MPI_Probe). */
void farm_nap(void);

#endif /* STRAY_MPI_FARM_PROTO_H */
