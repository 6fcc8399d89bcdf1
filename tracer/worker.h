/*
 * worker.h - private to the tracer: the state the trace's worker threads
 * share (integrator.c traces paths; trace.c runs the passes).
 */
#ifndef TRACER_WORKER_H
#define TRACER_WORKER_H

#include <pthread.h>

#include "tracer/guide.h"
#include "tracer/integrator.h"

struct worker_ctx {
	const struct tracer_scene *s;
	const struct tracer_trace_opts *o;
	struct tracer_result *res;
	struct vec3 *dir;		/* source direction per angle */
	double *dir_x, *dir_y, *dir_z;	/* the same, one array a component */
	double *beam_ok;		/* 1: the source is in front of the aperture */
	double *direct_ok;		/* 1: ... and the detector accepts it */
	double *beam_cx, *beam_cy, *beam_cz;	/* beam centre per angle */
	int angles_sorted;		/* theta ascending in [-180, 180]:
					 * tracer_screen_range may prune */
#define TRACER_RANGE_SHIFTS 16
	/* opts.beam_shift_z's distinct values (n_shifts < 0: more) */
	double shifts[TRACER_RANGE_SHIFTS];
	int n_shifts;
	struct tracer_path_table *batch_tables;
	double *batch_maps;		/* [batch][pixel] */
	struct frame focal_frame;	/* the pupil's frame (focal cells) */
	const struct tracer_guide *guide;	/* main pass: sample by it */
	double *pilot_s2;		/* pilot pass: [batch][cell][theta] */
	/* strategy B (light.c): B samples per path per angle, or NULL;
	 * pilot pass: [batch][theta][TRACER_LIGHT_STATS] B's statistics */
	const double *light_ratio;
	double *light_pilot;
	pthread_mutex_t lock;
	int next_batch, end_batch, done_batches;	/* batches [first, end) */
	int n_run;			/* end - first, for progress */
	int failed;
};

/* Trace batches until none is left (a pthread start routine). */
void *tracer_worker(void *arg);

/* Map pixel of detector point x (detector frame), or -1 outside. */
long tracer_map_pixel(const struct worker_ctx *w, struct vec3 x);

/* First path index of batch b. */
uint64_t tracer_batch_start(const struct tracer_result *r, int b);

#endif /* TRACER_WORKER_H */
