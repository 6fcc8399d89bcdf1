/*
 * diag.h - `stray diagnose`: what the simulation gets wrong against a
 * measured attenuation curve, which physical cause explains it, and what
 * the corrected model changes (issue 5; thesis §4, the photometer sweep
 * that the ray-traced curve under-predicted).
 *
 * Pieces, one file each:
 *   - the model state (every knob a cause can turn) and the registry of
 *     causes, cause_<name>.c (one self-contained file per cause);
 *   - the evaluator (evaluate.c): a state -> alpha(theta_i) with sigma.
 *     Geometry is traced once per node of a parameter grid (common random
 *     numbers: one seed) and cached; reflectance is re-weighted from the
 *     recorded path table (tracer/paths.h); angle offset, floor and leak
 *     post-process the curve;
 *   - the fit (fit.c, lm.c): weighted least squares of log10 residuals,
 *     each cause alone and greedy combinations ranked by BIC, profile-chi2
 *     intervals;
 *   - the report (report.c, report_json.c, plot_diag.c).
 */
#ifndef STRAY_TOOLS_DIAG_H
#define STRAY_TOOLS_DIAG_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

#define DIAG_PARAMS_MAX 3	/* per cause */
#define DIAG_COMBO_MAX 3	/* causes named together at most */
#define DIAG_FIT_PMAX (DIAG_PARAMS_MAX * DIAG_COMBO_MAX)
#define DIAG_SETS_MAX 32	/* user --set overrides */

/* Geometry axes: each changes the mesh or the detector, so a new trace. */
enum diag_geo {
	DIAG_GEO_EDGE_RADIUS,	/* mm, knife-edge fillet */
	DIAG_GEO_ACCEPT,	/* deg, detector acceptance half-angle; 90 = all */
	DIAG_GEO_BEVEL_UPPER,	/* 0 lower (design) or 1 upper face */
	DIAG_GEO_ABG_G,		/* ABg slope g; 0 = Lambertian (design) */
	DIAG_GEO_PIVOT,		/* mm, rotation centre behind the aperture */
	DIAG_GEO_N
};

/* Every knob a cause can turn; the nominal state reproduces the scene. */
struct diag_state {
	double reflectance;	/* interior scale vs the scene's; NaN: scene */
	double geo[DIAG_GEO_N];
	double angle_offset_deg;	/* stage zero: true = nominal + offset */
	double floor;		/* additive, linear alpha */
	double leak_log10;	/* leak level; -inf: none */
	double leak_lo_deg, leak_hi_deg;
};

void diag_state_nominal(struct diag_state *s);

/* How a cause reaches the model (the evaluator's cost). */
enum diag_kind { DIAG_REWEIGHT, DIAG_RETRACE, DIAG_POSTPROC };

struct diag_param {
	const char *name, *unit;
	double nominal, lo, hi;
	int n_start;		/* coarse-grid starting points of the fit */
};

struct diag_cause {
	const char *name;
	enum diag_kind kind;
	const char *explanation;	/* one paragraph, printed */
	int n_params;
	struct diag_param param[DIAG_PARAMS_MAX];
	int k_bic;		/* parameters counted by BIC (discrete: 1) */
	void (*apply)(const double *p, struct diag_state *s);
	/* RETRACE: the axis it turns and the traced nodes along it. */
	int geo_axis;
	const double *nodes;
	int n_nodes;
	/* Causes that need the parametric baffle (not a scene file). */
	int needs_baffle;
	/* Optional starting points (rows of n_params) from the angles;
	 * NULL: the product grid of each parameter's n_start values. */
	int (*start_grid)(const double *theta_deg, size_t n,
			  double (*out)[DIAG_PARAMS_MAX], int max);
};

/* The registry, in cli.md order; NULL-terminated. */
extern const struct diag_cause *const diag_causes[];
const struct diag_cause *diag_cause_find(const char *name);

/* ---- measured data ---- */
struct diag_data {
	size_t n;
	double *theta_deg, *alpha, *sigma;
	int *region;		/* enum diag_region */
};

enum diag_region { DIAG_IN_FIELD, DIAG_TRANSITION, DIAG_SCATTER,
		   DIAG_REGIONS };
extern const char *const diag_region_name[DIAG_REGIONS];

/* Load a measured curve (sigma column required); drops nothing silently:
 * a non-positive alpha or sigma is an error naming the row. */
int diag_data_load(const char *path, struct diag_data *d,
		   struct stray_error *err);
void diag_data_free(struct diag_data *d);

/* ---- evaluator ---- */
struct diag_trace;	/* a cached trace (evaluate.c) */

struct diag_eval {
	const char *scene;
	const char *sets[DIAG_SETS_MAX];
	int n_sets;
	int parametric;		/* scene is the built-in baffle */
	uint64_t n_paths, seed;
	int threads;
	const double *theta_deg;	/* measured angles */
	size_t n;
	double sub_step_deg;	/* fine grid for the angle offset */
	/* cache */
	struct diag_trace **cache;
	size_t n_cache, cap_cache;
	size_t n_traces;
	double trace_seconds;
	double *direct_share;	/* nominal direct / total at theta_i */
};

#define DIAG_SUB 9		/* fine-grid points per angle: -4..4 steps */
#define DIAG_OFFSET_MAX_DEG 1.0

void diag_eval_init(struct diag_eval *e, const char *scene,
		    const double *theta_deg, size_t n);
/* After sets are added: scene radii, the nominal trace, direct shares. */
int diag_eval_prepare(struct diag_eval *e, struct stray_error *err);
/* Model alpha and its sigma at the measured angles; relcov (n x n, may
 * be NULL) the relative covariance of the simulation errors. */
int diag_eval_model(struct diag_eval *e, const struct diag_state *s,
		    double *alpha, double *sigma, double *relcov,
		    struct stray_error *err);
void diag_eval_free(struct diag_eval *e);

/* ---- fit ---- */
struct diag_fit {
	int n_causes;
	const struct diag_cause *cause[DIAG_COMBO_MAX];
	int n_p;
	double p[DIAG_FIT_PMAX];
	double ci_lo[DIAG_FIT_PMAX], ci_hi[DIAG_FIT_PMAX];
	double chi2, bic;
	int k;
	int converged;
};

/* chi2 of the state's model against the data, measurement errors and the
 * correlated simulation errors combined; resid, resid_sigma (diagonal),
 * model and white (whitened residuals, chi2 = |white|^2) may be NULL. */
int diag_chi2(struct diag_eval *e, const struct diag_data *d,
	      const struct diag_state *s, double *chi2, double *resid,
	      double *resid_sigma, double *model, double *white,
	      struct stray_error *err);

/* The state of a fit's causes at parameters p. */
void diag_fit_state(const struct diag_fit *f, const double *p,
		    struct diag_state *s);

/* Fit the causes already set in f (their parameters), from the starts
 * in f->p when warm, else from each cause's coarse grid. */
int diag_fit_run(struct diag_eval *e, const struct diag_data *d,
		 struct diag_fit *f, int warm, struct stray_error *err);

/* Profile-chi2 intervals: delta chi2 = DIAG_CI_DCHI2 max(1, reduced
 * chi2); 9 is the 3-sigma (99.7 %) interval of one parameter. */
#define DIAG_CI_DCHI2 9.0
int diag_fit_intervals(struct diag_eval *e, const struct diag_data *d,
		       struct diag_fit *f, struct stray_error *err);

/* Levenberg-Marquardt on bounded parameters (lm.c). */
typedef int (*diag_resid_fn)(void *user, const double *p, double *r,
			     struct stray_error *err);
int diag_lm(diag_resid_fn fn, void *user, int n_p, size_t n_r, double *p,
	    const double *lo, const double *hi, double *chi2,
	    struct stray_error *err);

/* ---- diagnosis ---- */
#define DIAG_BIC_MARGIN 10.0	/* Kass & Raftery 1995: "very strong" */
#define DIAG_P_ACCEPT 0.01

struct diag_result {
	double chi2_before, chi2_after, p_before, p_after;
	int dof_before, dof_after;
	double rms_before, rms_after;
	double rms_region_before[DIAG_REGIONS], rms_region_after[DIAG_REGIONS];
	int n_region[DIAG_REGIONS];
	int significant;	/* the baseline does not fit */
	int explained;		/* the final model fits (p >= DIAG_P_ACCEPT) */
	struct diag_fit named;	/* the causes named (n_causes may be 0) */
	struct diag_fit tentative;	/* best model when unexplained */
	struct diag_fit single[16];	/* each cause alone */
	int n_single;
	double *model_before, *model_after, *resid_before, *resid_after;
	double *rsig_before, *rsig_after;
	double worst_theta_deg, worst_pull;	/* largest final residual */
	double sun_deg_before, sun_deg_after, sun_alpha_req;
};

/* Run the whole diagnosis; progress lines go to log when not NULL. */
int diag_run(struct diag_eval *e, const struct diag_data *d,
	     struct diag_result *r, void (*log)(const char *line),
	     struct stray_error *err);
void diag_result_free(struct diag_result *r);

/* Survival function of chi2 with dof degrees of freedom. */
double diag_chi2_pvalue(double chi2, int dof);

/* Sun exclusion angle of a curve at the sensor (st16-like by default). */
int diag_sun_exclusion(const double *theta_deg, const double *alpha,
		       size_t n, double *theta_excl, double *alpha_req,
		       struct stray_error *err);

/* ---- report ---- */
void diag_report_text(const struct diag_data *d, const struct diag_eval *e,
		      const struct diag_result *r);
int diag_report_json(const struct diag_data *d, const struct diag_eval *e,
		     const struct diag_result *r);
int diag_plot(const char *path, const struct diag_data *d,
	      const struct diag_result *r, struct stray_error *err);

#endif /* STRAY_TOOLS_DIAG_H */
