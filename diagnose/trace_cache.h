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

/* Power and variance per traced angle at interior reflectance rho
 * (NaN: the scene's). */
void diag_trace_power(const struct diag_trace *t, double rho, double *p,
		      double *var);

/* The same with rho(l) = rho (l / l0)^slope over the current band
 * (diagnose/spectral.c). */
void diag_trace_power_band(const struct diag_trace *t, double rho,
			   double slope, double *p, double *var);

#endif /* DIAGNOSE_TRACE_CACHE_H */
