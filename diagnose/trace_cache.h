/*
 * trace_cache.h - the evaluator's internals shared by evaluate.c and
 * trace_cache.c: a cached trace reduced for re-weighting (private to
 * diagnose/).
 */
#ifndef DIAGNOSE_TRACE_CACHE_H
#define DIAGNOSE_TRACE_CACHE_H

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

/* The pivot-offset nodes of one geometry traced in one pass
 * (trace_beams.c): ts[0..K) set up by the cache, the same geometry but
 * for their DIAG_GEO_PIVOT. */
#define DIAG_PIVOT_NODES_MAX 16
int diag_trace_beams(struct diag_eval *e, struct diag_trace **ts, size_t K,
		     struct stray_error *err);

/* The cached trace of a geometry (traced on first use; a pivot-offset
 * node with every other node of its axis at that geometry). */
int diag_trace_get(struct diag_eval *e, const double *geo, int fine,
		   const struct diag_trace **out, struct stray_error *err);
void diag_trace_cache_free(struct diag_eval *e);

/* Power and variance per traced angle at interior reflectance rho
 * (NaN: the scene's). */
void diag_trace_power(const struct diag_trace *t, double rho, double *p,
		      double *var);

/* The same with rho(l) = rho (l / l0)^slope over the current band
 * (diagnose/spectral.c). */
void diag_trace_power_band(const struct diag_trace *t, double rho,
			   double slope, double *p, double *var);

#endif /* DIAGNOSE_TRACE_CACHE_H */
