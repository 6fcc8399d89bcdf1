/*
 * trace_cache.h - the evaluator's internals shared by evaluate.c and
 * trace_cache.c: the traces cached by geometry key, and their power at a
 * reflectance (private to diagnose/; one trace: trace_scene.h).
 */
#ifndef DIAGNOSE_TRACE_CACHE_H
#define DIAGNOSE_TRACE_CACHE_H

#include "trace_scene.h"

/* The cached trace of a geometry (traced on first use; a pivot-offset
 * node with every other node of its axis at that geometry). */
int diag_trace_get(struct diag_eval *e, const double *geo, int fine,
		   const struct diag_trace **out, struct stray_error *err);
void diag_trace_cache_free(struct diag_eval *e);
/* Room for `more` traces, so that making them does not move the list
 * (candidates.c: a thread reads it meanwhile). */
int diag_trace_cache_reserve(struct diag_eval *e, size_t more,
			     struct stray_error *err);

/* Power and variance per traced angle at interior reflectance rho
 * (NaN: the scene's). */
void diag_trace_power(const struct diag_trace *t, double rho, double *p,
		      double *var);

/* The same with rho(l) = rho (l / l0)^slope over the current band
 * (diagnose/spectral.c). */
void diag_trace_power_band(const struct diag_trace *t, double rho,
			   double slope, double *p, double *var);

/* alpha and relative variance at the centre of each measured angle (and
 * at the fine sub-points with all_sub), for one trace at the coating
 * (rho, slope) (geometry_blend.c). */
void diag_trace_alpha(const struct diag_eval *e, const struct diag_trace *t,
		      double rho, double slope, double *p, double *var,
		      double *alpha, double *relvar, int all_sub);

/* alpha at the measured angles and the relative covariance of the state's
 * geometry at its coating, blended between traced nodes; work holds
 * 2 (n DIAG_SUB + 1) + 2 n DIAG_SUB + 2 n doubles (geometry_blend.c). */
int diag_blend_geometry(struct diag_eval *e, const struct diag_state *s,
			double *work, double *alpha, double *relcov,
			struct stray_error *err);

#endif /* DIAGNOSE_TRACE_CACHE_H */
