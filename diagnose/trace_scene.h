/*
 * trace_scene.h - one trace of the evaluator's cache (trace_scene.c): the
 * trace reduced for re-weighting, and the scene it is traced on at a
 * geometry key (private to diagnose/).
 */
#ifndef DIAGNOSE_TRACE_SCENE_H
#define DIAGNOSE_TRACE_SCENE_H

#include "diagnose/diag_eval.h"
#include "tracer/detector.h"
#include "tracer/integrator.h"
#include "tracer/runner.h"
#include "tracer/scene.h"

struct diag_trace {
	double geo[DIAG_GEO_N];	/* the key; NaN: the scene's own */
	int fine;		/* angles theta_i + k step, not theta_i */
	size_t n_theta, ref;	/* traced angles; ref: theta = 0 */
	double *theta;
	size_t *idx;		/* [measured][DIAG_SUB] -> traced index */
	double *direct;		/* direct share of the power, per angle */
	double *relcov;		/* [n][n] relative covariance of alpha at the
				 * measured angles, from the batches */
	double base_rho;	/* the scene's interior reflectance */
	size_t n_e;		/* path-table rows */
	unsigned *j;
	unsigned char *n_int;
	double *v, *var;
};

/* A geometry's scene as the trace cache builds it: --set list, the
 * runner's description (its edits), the scene and the lens table.  The
 * spec points into the struct: build it in place, do not copy it. */
struct diag_scene {
	char buf[3][64];
	const char *sets[DIAG_SETS_MAX + 3];
	struct tracer_scene_spec spec;
	struct tracer_scene s;
	struct tracer_lens lens;
};

int diag_scene_build(const struct diag_eval *e, const double *geo,
		     struct diag_scene *ds, struct stray_error *err);
void diag_scene_free(struct diag_scene *ds);
/* Can the scene be built at this geometry (scene_causes.c's grid)? */
int diag_geometry_check(const struct diag_eval *e, const double *geo,
			struct stray_error *err);

/* The options every trace of the cache uses (t's angles and paths). */
void diag_trace_opts(const struct diag_eval *e, const struct diag_trace *t,
		     const struct diag_scene *ds, struct tracer_trace_opts *o);

/* t's tables (direct share, path rows, covariance) from a trace r of
 * scene s at t's angles. */
int diag_trace_fill(struct diag_eval *e, struct diag_trace *t,
		    const struct tracer_result *r, const struct tracer_scene *s,
		    struct stray_error *err);

#endif /* DIAGNOSE_TRACE_SCENE_H */
