/*
 * trace_job.h - a run of `stray trace` as library calls: the caller loads
 * the scene (tracer/scene_load.h) and fills the job's inputs and its
 * tracer options; tracer_job_prepare commits the scene and sets the
 * angles, lens and band; the caller may then ask for focal-plane sums or
 * maps at one of the angles (tracer_job_angle_index); tracer_job_run
 * traces through the job's runner; tracer_job_write_curve writes the
 * curve.  `stray trace` (tools/cmd_trace.c), `stray-mpi` (its runner)
 * and Python call the same functions.
 */
#ifndef STRAY_TRACER_TRACE_JOB_H
#define STRAY_TRACER_TRACE_JOB_H

#include <stddef.h>

#include "stray/curve_io.h"
#include "stray/error.h"
#include "tracer/detector.h"
#include "tracer/integrator.h"
#include "tracer/runner.h"
#include "tracer/spectral.h"

#define TRACER_JOB_SETS_MAX 64

/* The scatter-order columns of a curve file: direct, 1, 2, 3+. */
extern const char *const tracer_order_names[TRACER_ORDERS];

struct tracer_job {
	/* inputs */
	const struct tracer_runner *runner;	/* who runs the trace */
	const char *scene;	/* 'ref4' or a scene file */
	const char *sets[TRACER_JOB_SETS_MAX];	/* --set key=value */
	int n_sets;
	const char *angles;	/* an angle list (tracer/angles.h) */
	int auto_angles;	/* 1: the grid fitted to the direct cut-off */
	const char *lens;	/* a lens curve or ideal:DEG; NULL: none */
	const char *spectrum, *response;	/* tracer/spectral.h */
	const char *scene_note;	/* what loading the scene changed */
	struct tracer_trace_opts o;
	/* filled by tracer_job_prepare */
	double cutoff_deg;	/* the direct cut-off the auto grid found */
	double *theta;		/* the angles traced, 0 first */
	size_t n_theta;
	size_t first;		/* 1 when 0 was added as the reference */
	struct tracer_lens lens_model;
	struct tracer_band band;
};

/* Commit the scene; the angles (with 0 added as the reference angle
 * alpha is normalised to), the lens and the spectral band into j->o. */
int tracer_job_prepare(struct tracer_job *j, struct tracer_scene *s,
		       struct stray_error *err);

/* The index of angle_deg among the traced angles; an error naming
 * --map-angle when it is not one of them. */
int tracer_job_angle_index(const struct tracer_job *j, double angle_deg,
			   size_t *k, struct stray_error *err);

/* Trace through j->runner, weight by the band, and refuse a scene where
 * no on-axis power reaches the detector (alpha would be 0/0).  On
 * success the caller frees r (tracer_result_free). */
int tracer_job_run(struct tracer_job *j, struct tracer_scene *s,
		   struct tracer_result *r, struct stray_error *err);

/* The curve (alpha, sigma, one column per scatter order) and its
 * provenance (kind, scene, lens, mesh, source, sigma, angles), the
 * reference angle left out when it was added; the caller frees *out
 * (stray_curve_free) on success. */
int tracer_job_curve(const struct tracer_job *j,
		     const struct tracer_result *r, struct stray_curve *out,
		     struct stray_error *err);

/* The same curve written to path (stray/curve_io.h). */
int tracer_job_write_curve(const struct tracer_job *j,
			   const struct tracer_result *r, const char *path,
			   struct stray_error *err);

/* The job's angles and lens (the job itself is the caller's). */
void tracer_job_free(struct tracer_job *j);

#endif /* STRAY_TRACER_TRACE_JOB_H */
