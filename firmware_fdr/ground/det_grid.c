/*
 * det_grid.c - the named detector carried into the flight table (issue
 * 28, table version 3): the ground solves, with libstray's validated
 * models (stray/detector.h), what the module would otherwise compute on
 * board, and the module reads it back by interpolation.
 *
 * The grid is in ln I_px, the stray photo-electrons per pixel of eq. 2.3:
 * every body's light at any attenuation reaches the detector models only
 * through it (their thresholds are set by the DRS and the camera's noise
 * at the table's exposure).  FDRFW_DET_PER_DECADE nodes a decade, the
 * Sun's binding background exactly on node FDRFW_DET_BELOW, so the flag
 * turns on where `stray exclusion --detector D` puts alpha_required and
 * the Sun's exclusion angle is the ground's to float rounding.
 */
#include <math.h>
#include <stdio.h>

#include "fdrfw/table_build.h"
#include "stray/errfmt.h"

/* The model of a named detector: the thesis's plus the camera's read
 * noise and dark current (the detectors are validated with them, as
 * tools/fdr_setup.c sets them for `stray fdr`/`exclusion`). */
static void det_model(const struct stray_sensor *s,
		      const struct stray_fdr_model *m,
		      struct stray_fdr_model *g)
{
	*g = *m;
	g->read_noise_e = s->read_noise_e;
	g->dark_current_e_s = s->dark_current_e_s;
}

int fdrfw_det_setup(const struct stray_sensor *s,
		    const struct fdrfw_build_params *p,
		    const struct stray_fdr_model *m, struct stray_detector *d,
		    struct stray_fdr_model *g, struct stray_error *err)
{
	det_model(s, m, g);
	stray_detector_init(d, p->detector, s->star_window_px);
	d->sigma_k = p->detector_sigma > 0.0 ? p->detector_sigma : 3.0;
	return stray_detector_setup(d, g, err);
}

/* Node i's value of both models: ln false stars (floored, capped) and
 * the DRS's detection probability. */
static int node(const struct stray_detector *d, const struct stray_fdr_model *g,
		double alpha, float *ln_false, float *p_drs,
		struct stray_error *err)
{
	double lf, p;
	int rc;

	if ((rc = stray_detector_log_false_rate(d, g, alpha, &lf, err)) ||
	    (rc = stray_detector_star_prob(d, g, alpha,
					   stray_fdr_drs_photons(g), &p, err)))
		return rc;
	if (isnan(lf) || isnan(p))
		return stray_error_set_value(err, STRAY_ERANGE, "alpha",
			"the detector model gave no number here", alpha);
	*ln_false = (float)fmin(1e3, fmax(lf, (double)FDRFW_DET_LN_FLOOR));
	*p_drs = (float)fmin(1.0, fmax(p, 0.0));
	return STRAY_OK;
}

/* alpha of the Sun's light that gives I_px = e^u (eq. 2.3). */
static double node_alpha(const struct stray_fdr_model *g, double u)
{
	return exp(u) / stray_fdr_pixel_photons(g, 1.0);
}

int fdrfw_det_grid_fill(const struct stray_detector *d,
			const struct stray_fdr_model *g, double alpha_req,
			struct fdrfw_table *t, struct stray_error *err)
{
	double du = log(10.0) / FDRFW_DET_PER_DECADE;
	double u_req = log(stray_fdr_pixel_photons(g, alpha_req));
	int i;

	if (!isfinite(u_req))
		return stray_error_set_value(err, STRAY_ERANGE, "alpha",
			"the binding background is not a number of photons",
			alpha_req);
	t->detector = (uint32_t)d->kind;
	t->detector_sigma = d->kind == STRAY_DET_TETRA3 ? (float)d->sigma_k
							: 0.0f;
	t->n_det = FDRFW_DET_MAX;
	t->det_du = (float)du;
	t->det_u0 = (float)(u_req - FDRFW_DET_BELOW * (double)t->det_du);
	if (!(fabs((double)t->det_u0) <= 60.0))
		return stray_error_set_value(err, STRAY_ERANGE, "det_u0",
			"the detector grid's background lies outside "
			"e^-60..e^60 e- per pixel", (double)t->det_u0);
	for (i = 0; i < FDRFW_DET_MAX; i++) {
		double u = (double)t->det_u0 + i * (double)t->det_du;
		int rc = node(d, g, node_alpha(g, u), &t->det_ln_false[i],
			  &t->det_p_drs[i], err);
		if (rc != STRAY_OK)
			return rc;
	}
	/* The models rise/fall with the light; a quadrature's last digit
	 * may not: the conservative side (more false stars, a lower P)
	 * keeps both monotone, as the module's check asks. */
	for (i = 1; i < FDRFW_DET_MAX; i++) {
		t->det_ln_false[i] = fmaxf(t->det_ln_false[i],
					   t->det_ln_false[i - 1]);
		t->det_p_drs[i] = fminf(t->det_p_drs[i], t->det_p_drs[i - 1]);
	}
	return STRAY_OK;
}

double fdrfw_det_node_alpha(const struct fdrfw_table *t, double f_src,
			    int i)
{
	double per_alpha = f_src * (double)t->t_exp_nominal_s *
			   (double)t->a_px_m2 * (double)t->k_px;

	return exp((double)t->det_u0 + i * (double)t->det_du) / per_alpha;
}

enum stray_failure_mode fdrfw_table_binding(const struct fdrfw_table *t)
{
	/* just past the Sun's binding node: which requirement failed */
	int i = FDRFW_DET_BELOW + 1;

	if (t->n_det == 0u)
		return STRAY_FAIL_FALSE_STARS;
	return t->det_p_drs[i] < t->pr_drs &&
	       !((double)t->det_ln_false[i] >= log((double)t->fdr_tolerated)) ?
		STRAY_FAIL_LOST_STARS : STRAY_FAIL_FALSE_STARS;
}

const char *fdrfw_table_detector_name(const struct fdrfw_table *t)
{
	const char *n = t->detector < FDRFW_DET_KINDS ?
		stray_detector_name((enum stray_detector_kind)t->detector) : NULL;

	return n ? n : "unknown";
}

/* The reasons are static (struct stray_error keeps a pointer). */
static const char *const asked[STRAY_DET_COUNT] = {
	"asked for thesis, but the table was built for this one: "
	"rebuild it with stray firmware-table --detector thesis",
	"asked for window, but the table was built for this one: "
	"rebuild it with stray firmware-table --detector window",
	"asked for threshold, but the table was built for this one: "
	"rebuild it with stray firmware-table --detector threshold",
	"asked for tetra3, but the table was built for this one: "
	"rebuild it with stray firmware-table --detector tetra3",
};

int fdrfw_table_detector_check(const struct fdrfw_table *t,
			       enum stray_detector_kind kind, double sigma,
			       const char *path, struct stray_error *err)
{
	char text[48];
	int rc;

	if ((unsigned)kind >= STRAY_DET_COUNT)
		return stray_error_set(err, STRAY_EINVAL, "detector",
				       "unknown detector");
	if (t->detector == (uint32_t)kind &&
	    (kind != STRAY_DET_TETRA3 ||
	     fabs((double)t->detector_sigma - sigma) <= 1e-6 * sigma))
		return STRAY_OK;
	if (t->detector == (uint32_t)kind) {
		snprintf(text, sizeof(text), "tetra3, k = %g",
			 (double)t->detector_sigma);
		rc = stray_error_at(err, STRAY_EINVAL, path, 0, "detector",
			"the table's tetra3 threshold is another k sigma than "
			"asked: rebuild it with stray firmware-table --detector "
			"tetra3 --detector-sigma K");
	} else {
		snprintf(text, sizeof(text), "%s", fdrfw_table_detector_name(t));
		rc = stray_error_at(err, STRAY_EINVAL, path, 0, "detector",
				    asked[kind]);
	}
	stray_error_text(err, text);
	return rc;
}
