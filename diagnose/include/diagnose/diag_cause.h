/*
 * diag_cause.h - the diagnosis's model state (every knob a cause can
 * turn) and the registry of physical causes, one self-contained file
 * each (diagnose/cause_<name>.c).  The library's pieces:
 *   - diag_cause.h: state and registry;
 *   - diag_data.h: the measured curve and its angle regions;
 *   - diag_eval.h: the evaluator, a state -> alpha(theta_i) with sigma.
 *     Geometry is traced once per node of a parameter grid (common random
 *     numbers: one seed) and cached (diagnose/trace_cache.c, through the
 *     caller's tracer runner); reflectance is re-weighted from the
 *     recorded path table (tracer/paths.h); angle offset, floor and leak
 *     post-process the curve;
 *   - diag_fit.h: weighted least squares of log10 residuals, each cause
 *     alone and greedy combinations ranked by BIC, profile-chi2
 *     intervals;
 *   - diag_result.h: the whole diagnosis as data (what `stray diagnose`
 *     prints, plots and writes as JSON in tools/).
 * (Issue 5; thesis §4, the photometer sweep that the ray-traced curve
 * under-predicted.)
 */
#ifndef DIAGNOSE_DIAG_CAUSE_H
#define DIAGNOSE_DIAG_CAUSE_H

#include <stddef.h>

#define DIAG_PARAMS_MAX 3	/* per cause */
#define DIAG_OFFSET_MAX_DEG 1.0	/* bound of the stage-zero angle offset */

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
	double scale_log10;	/* the whole curve x 10^this; 0: none */
	/* issue 17 item 5: rho(l) = rho0 (l / l0)^slope, weighted by the
	 * source spectrum x response (diag_spectral.h); 0: grey */
	double spectral_slope;
	/* issue 17 item 6: the lab beam's directions, a disk of this
	 * half-angle (deg; 0: collimated) ... */
	double beam_half_deg;
	/* ... with a Gaussian fall-off of this 1/e^2 radius (deg) inside it
	 * (0: uniform over the disk) */
	double beam_gauss_deg;
	/* system curves (--lens): the lens table's out-of-field part x
	 * 10^lens_log10 (0: none); a ghost, the table x 10^ghost_log10
	 * between ghost_lo_deg and ghost_hi_deg (-inf: none) */
	double lens_log10;
	double ghost_log10, ghost_lo_deg, ghost_hi_deg;
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
	/* Causes that need the parametric vane family (ref4 or a "type":
	 * "vanes" scene file), not a mesh scene. */
	int needs_baffle;
	/* Causes only for curves with no theta = 0 point: a curve that has
	 * one is normalised by it, its scale is not free (a flight curve,
	 * `stray flightcheck --out`, is absolute and has none). */
	int needs_unnormalised;
	/* Lens causes: only for system curves (`--lens`); named on the
	 * lens's side of the report. */
	int needs_lens;
	/* Optional starting points (rows of n_params) from the angles;
	 * NULL: the product grid of each parameter's n_start values. */
	int (*start_grid)(const double *theta_deg, size_t n,
			  double (*out)[DIAG_PARAMS_MAX], int max);
	/* The simpler cause this one extends (its limit at some parameter
	 * value), or NULL: a named extension gives way to it unless it
	 * lowers BIC by the margin (run.c, simplify). */
	const char *nests;
};

/* The registry, in cli.md order; NULL-terminated. */
extern const struct diag_cause *const diag_causes[];
const struct diag_cause *diag_cause_find(const char *name);

#endif /* DIAGNOSE_DIAG_CAUSE_H */
