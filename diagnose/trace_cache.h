/*
 * trace_cache.h - the evaluator's internals shared by evaluate.c and
 * trace_cache.c: a cached trace reduced for re-weighting (private to
 * diagnose/).
 */
#ifndef DIAGNOSE_TRACE_CACHE_H
#define DIAGNOSE_TRACE_CACHE_H

#include "diagnose/diag_eval.h"

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

/* The cached trace of a geometry (traced on first use). */
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
