/*
 * exclusion.c - what a model correction means in orbit: the Sun exclusion
 * angle of the model curve (thesis §5.1, fig. 5.1) for the sensor given
 * (`stray diagnose --sensor`, st16-like by default), alpha_required from the FDR model at the Sun's photon flux and
 * the sensor's tolerated false-detection rate.  The sensor as `stray
 * exclusion` sees it with no option: its own spectra, the thesis's
 * Gaussian shot noise, uniform stray light, no detector noise.
 */
#include <math.h>
#include <stdio.h>

#include "diagnose/diag_result.h"
#include "stray/curve.h"
#include "stray/detector.h"
#include "stray/errfmt.h"
#include "stray/fdr.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"
#include "stray/sensor_io.h"

/* alpha_required of the named detector (issue 28): the first of its two
 * failure modes, with the camera's read noise and dark current, as
 * `stray exclusion --detector D` (tools/fdr_setup.c). */
static int detector_req(const struct stray_sensor *sn,
			const struct stray_fdr_model *m0,
			struct diag_detector *dd, double *alpha_req,
			struct stray_error *err)
{
	struct stray_fdr_model m = *m0;
	struct stray_detector d;
	struct stray_detector_req r;
	int rc;

	m.read_noise_e = sn->read_noise_e;
	m.dark_current_e_s = sn->dark_current_e_s;
	stray_detector_init(&d, dd->kind, sn->star_window_px);
	d.sigma_k = dd->sigma > 0.0 ? dd->sigma : 3.0;
	if ((rc = stray_detector_setup(&d, &m, err)) != STRAY_OK ||
	    (rc = stray_detector_alpha_required(&d, &m, sn->fdr_tolerated,
						sn->pr_drs, &r, err)))
		return rc;
	*alpha_req = r.alpha_req;
	dd->binding = r.binding;
	return STRAY_OK;
}

int diag_sun_exclusion(const char *spec, const double *theta_deg,
		       const double *alpha, size_t n, double *theta_excl,
		       double *alpha_req, char *name,
		       struct stray_error *err)
{
	return diag_sun_exclusion_det(spec, NULL, theta_deg, alpha, n,
				      theta_excl, alpha_req, name, err);
}

int diag_sun_exclusion_det(const char *spec, struct diag_detector *dd,
			   const double *theta_deg, const double *alpha,
			   size_t n, double *theta_excl, double *alpha_req,
			   char *name, struct stray_error *err)
{
	struct stray_sensor sensor;
	struct stray_fluxes flux;
	struct stray_fdr_model m;
	struct stray_curve_view v = { n, theta_deg, alpha, NULL };
	int rc = stray_sensor_load(spec ? spec : "st16-like", &sensor, err);

	if (!rc && name)
		snprintf(name, 64, "%s", sensor.name);
	if (!rc)
		rc = stray_reference_fluxes(&sensor, &flux, err);
	if (rc)
		return rc;
	stray_sensor_fdr_model(&sensor, flux.sun, flux.drs, &m);
	rc = stray_fdr_model_check(&m, err);
	if (dd && !dd->name) {	/* no --detector: the sensor file's */
		dd->kind = STRAY_DET_THESIS;
		if (sensor.detector[0])
			stray_detector_parse(sensor.detector, &dd->kind, NULL);
		if (!(dd->sigma > 0.0) && sensor.detector_sigma > 0.0)
			dd->sigma = sensor.detector_sigma;
	}
	if (dd)
		dd->binding = STRAY_FAIL_FALSE_STARS;
	if (!rc && dd && dd->kind != STRAY_DET_THESIS)
		rc = detector_req(&sensor, &m, dd, alpha_req, err);
	else if (!rc)
		rc = stray_fdr_alpha_required(&m, sensor.fdr_tolerated,
					      alpha_req, err);
	if (rc)
		return rc;
	rc = stray_exclusion_angle(&v, *alpha_req, theta_excl, err);
	if (rc == STRAY_ERANGE) {	/* a result: not excluded in range */
		stray_error_clear(err);
		*theta_excl = NAN;
		rc = STRAY_OK;
	}
	return rc;
}
