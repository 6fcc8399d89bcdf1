/*
 * diag_eval.h - the evaluator: a model state -> alpha at the measured
 * angles, with sigma and the correlated simulation errors.  Its traces
 * run through the caller's runner (tracer/runner.h): this process's
 * threads under `stray`, the MPI ranks under `stray-mpi`.
 */
#ifndef DIAGNOSE_DIAG_EVAL_H
#define DIAGNOSE_DIAG_EVAL_H

#include <stddef.h>
#include <stdint.h>

#include "diagnose/diag_cause.h"
#include "stray/error.h"

#define DIAG_SETS_MAX 32	/* user --set overrides */
#define DIAG_LENS_BINS_MAX 64

struct tracer_runner;
struct diag_trace;	/* a cached trace (diagnose/trace_cache.h) */

struct diag_eval {
	const char *scene;
	const char *sets[DIAG_SETS_MAX];
	int n_sets;
	int parametric;		/* scene is the built-in baffle */
	const char *lens;	/* lens table (system curve), or NULL */
	uint64_t n_paths, seed;
	int threads;
	const struct tracer_runner *runner;	/* runs every trace */
	const double *theta_deg;	/* measured angles */
	size_t n;
	double sub_step_deg;	/* fine grid for the angle offset */
	/* cache */
	struct diag_trace **cache;
	size_t n_cache, cap_cache;
	size_t n_traces;
	double trace_seconds;
	double *direct_share;	/* nominal direct / total at theta_i */
	/* system curves (diagnose/lens.c): light arriving per incidence bin
	 * beyond the lens's field, [bin][measured], and the nominal model */
	int n_lens_bins;
	double lens_bin_lo, lens_bin_first;	/* field edge, 2nd bin */
	double *lens_bin, *lens_alpha_nom;
};

#define DIAG_SUB 9		/* fine-grid points per angle: -4..4 steps */

void diag_eval_init(struct diag_eval *e, const char *scene,
		    const double *theta_deg, size_t n,
		    const struct tracer_runner *runner);
/* After sets are added: scene radii, the nominal trace, direct shares. */
int diag_eval_prepare(struct diag_eval *e, struct stray_error *err);
/* Model alpha and its sigma at the measured angles; relcov (n x n, may
 * be NULL) the relative covariance of the simulation errors. */
int diag_eval_model(struct diag_eval *e, const struct diag_state *s,
		    double *alpha, double *sigma, double *relcov,
		    struct stray_error *err);
void diag_eval_free(struct diag_eval *e);

#endif /* DIAGNOSE_DIAG_EVAL_H */
