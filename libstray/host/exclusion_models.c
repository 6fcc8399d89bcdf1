/*
 * exclusion_models.c - one curve's Sun exclusion angle under every model
 * (stray/exclusion_models.h): the same libstray functions as `stray
 * exclusion --normalisation N --detector D` (tools/fdr_setup.c), one row
 * per model, so the table is the command's answers side by side.
 */
#include <math.h>

#include "stray/exclusion_models.h"
#include "stray/fdr.h"

static const struct {
	const char *name;
	enum stray_detector_kind kind;
	double sigma;
	enum stray_normalisation norm;
} rows[STRAY_EXCL_MODELS] = {
	{ "thesis (eq. 2.18, k_px = 1)", STRAY_DET_THESIS, 0, STRAY_NORM_THESIS },
	{ "consistent (eq. 2.18)", STRAY_DET_THESIS, 0, STRAY_NORM_CONSISTENT },
	{ "window", STRAY_DET_WINDOW, 0, STRAY_NORM_CONSISTENT },
	{ "threshold", STRAY_DET_THRESHOLD, 0, STRAY_NORM_CONSISTENT },
	{ "tetra3, k = 3", STRAY_DET_TETRA3, 3, STRAY_NORM_CONSISTENT },
	{ "tetra3, k = 5", STRAY_DET_TETRA3, 5, STRAY_NORM_CONSISTENT },
};

/* alpha_required of one row, both failure modes for a detector. */
static int row_req(const struct stray_sensor *s, int i, double f_sun,
		   double f_drs, double rate, struct stray_excl_model *o,
		   struct stray_error *err)
{
	struct stray_fdr_model m;
	struct stray_detector d;
	struct stray_detector_req r;
	int rc;

	stray_sensor_fdr_model(s, f_sun, f_drs, &m);
	m.k_px = stray_sensor_k_px(s, rows[i].norm);
	o->k_px = m.k_px;
	if (rows[i].kind == STRAY_DET_THESIS) {
		o->alpha_lost = NAN;
		o->binding = STRAY_FAIL_FALSE_STARS;
		rc = stray_fdr_alpha_required(&m, rate, &o->alpha_false, err);
		o->alpha_req = o->alpha_false;
		return rc;
	}
	m.read_noise_e = s->read_noise_e;
	m.dark_current_e_s = s->dark_current_e_s;
	stray_detector_init(&d, rows[i].kind, s->star_window_px);
	d.sigma_k = rows[i].sigma > 0 ? rows[i].sigma : 3;
	if ((rc = stray_detector_setup(&d, &m, err)) != STRAY_OK ||
	    (rc = stray_detector_alpha_required(&d, &m, rate, s->pr_drs, &r,
						err)) != STRAY_OK)
		return rc;
	o->alpha_false = r.alpha_false;
	o->alpha_lost = r.alpha_lost;
	o->alpha_req = r.alpha_req;
	o->binding = r.binding;
	return STRAY_OK;
}

int stray_exclusion_models(const struct stray_curve_view *c,
			   const struct stray_sensor *s, double f_sun,
			   double f_drs, double rate,
			   struct stray_excl_model out[STRAY_EXCL_MODELS],
			   struct stray_error *err)
{
	struct stray_exclusion ex;
	int i, rc;

	if (!(rate > 0.0))
		rate = s->fdr_tolerated;
	for (i = 0; i < STRAY_EXCL_MODELS; i++) {
		struct stray_excl_model *o = &out[i];

		o->model = rows[i].name;
		o->detector = rows[i].kind;
		o->sigma_k = rows[i].sigma;
		if ((rc = row_req(s, i, f_sun, f_drs, rate, o, err)) ||
		    (rc = stray_exclusion_interval(c, o->alpha_req, 0.0, &ex,
						   err)))
			return rc;
		o->excluded = ex.excluded;
		o->sun_deg = ex.excluded ? ex.theta_deg : NAN;
		o->reason = ex.excluded ? NULL : ex.reason;
	}
	return STRAY_OK;
}
