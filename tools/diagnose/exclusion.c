/*
 * exclusion.c - what a model correction means in orbit: the Sun exclusion
 * angle of the model curve (thesis §5.1, fig. 5.1) for the st16-like
 * sensor, alpha_required from the FDR model at the Sun's photon flux and
 * the sensor's tolerated false-detection rate.
 */
#include <math.h>

#include "diag.h"
#include "fdr_setup.h"
#include "stray/curve.h"
#include "stray/errfmt.h"

int diag_sun_exclusion(const double *theta_deg, const double *alpha,
		       size_t n, double *theta_excl, double *alpha_req,
		       struct stray_error *err)
{
	struct fdr_setup s;
	struct stray_fdr_model m;
	struct stray_curve_view v = { n, theta_deg, alpha, NULL };
	int rc;

	fdr_setup_init(&s);
	rc = fdr_setup_load(&s, err);
	if (rc)
		return rc;
	fdr_setup_model(&s, s.flux.sun, &m);
	rc = stray_fdr_alpha_required(&m, s.sensor.fdr_tolerated, alpha_req,
				      err);
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
