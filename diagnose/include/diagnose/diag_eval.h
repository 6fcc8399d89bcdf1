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
#define DIAG_CAUSES_MAX 24	/* causes in the registry */
#define DIAG_NODES_MAX 16	/* grid nodes of a re-trace cause */
#define DIAG_NOTES_MAX 16	/* what the scene changed, said in the report */

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
	/* geometry axes (bit per enum diag_geo) whose effect is taken as a
	 * factor from their own nodes, the interaction with the other axes
	 * neglected: no trace of a combined grid (run.c's screen); 0 */
	unsigned factorized;
	/* threads fitting one greedy step's candidates (candidates.c; 0:
	 * two, 1: the caller's alone) */
	int fit_threads;
	/* a copy fitting beside the caller (candidates.c): a trace not
	 * cached is not made, missed set and an error returned */
	int no_trace, missed;
	/* the last geometry blend: its key, alpha then relcov (n + n^2) */
#define DIAG_BLEND_KEY (DIAG_GEO_N + 3)
	double blend_key[DIAG_BLEND_KEY], *blend_alpha;
	/* fit.c: what the last residual covariance was made of, its
	 * Cholesky factor (chol_ok 1, 0 not SPD, -1 none) and diag_chi2's
	 * work, one block for chol_n angles */
	double *chol_in, *chol_out;
	size_t chol_n;
	int chol_ok;
	/* system curves (diagnose/lens.c): light arriving per incidence bin
	 * beyond the lens's field, [bin][measured], and the nominal model */
	int n_lens_bins;
	double lens_bin_lo, lens_bin_first;	/* field edge, 2nd bin */
	double *lens_bin, *lens_alpha_nom;
	/* the registry fitted to this scene (diag_eval_prepare,
	 * diagnose/scene_causes.c): nominal values the scene's own, grid
	 * nodes the scene cannot be built with dropped (and said in notes),
	 * only the causes `only` names and none `without` names (comma
	 * lists, NULL: all); NULL-terminated; what the run fits */
	const char *only, *without;
	const char *sensor;	/* for the Sun exclusion; NULL: st16-like */
	/* its detector (--detector, --detector-sigma; NULL / 0: the sensor
	 * file's, else thesis / 3) */
	const char *detector;
	double detector_sigma;
	int normalised;		/* the curve has its theta = 0 row */
	const struct diag_cause *causes[DIAG_CAUSES_MAX + 1];
	struct diag_cause cause_own[DIAG_CAUSES_MAX];
	double node_own[DIAG_CAUSES_MAX][DIAG_NODES_MAX];
	char notes[DIAG_NOTES_MAX][200];
	int n_notes;
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

/* A comma list of cause names: NULL, or the first name not registered
 * (into bad, size n). */
const char *diag_causes_check(const char *list, char *bad, size_t n);

/* Fill e->causes from the registry for e's scene (called by
 * diag_eval_prepare after the nominal trace). */
int diag_eval_causes(struct diag_eval *e, double base_rho,
		     struct stray_error *err);

/* The retrace cause of a geometry axis among e->causes, or NULL. */
const struct diag_cause *diag_eval_axis_cause(const struct diag_eval *e,
					      int axis);

#endif /* DIAGNOSE_DIAG_EVAL_H */
