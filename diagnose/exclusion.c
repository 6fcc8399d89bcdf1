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
#include "stray/errfmt.h"
#include "stray/fdr.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"
#include "stray/sensor_io.h"

int diag_sun_exclusion(const char *spec, const double *theta_deg,
		       const double *alpha, size_t n, double *theta_excl,
		       double *alpha_req, char *name,
		       struct stray_error *err)
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
	if (!rc)
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
