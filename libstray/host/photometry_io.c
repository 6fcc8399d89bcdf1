/*
 * photometry_io.c - a sensor's reference-flux table (thesis §2.2,
 * table 2.1) from its spectra.
 */
#include "stray/photometry.h"
#include "stray/photometry_io.h"
#include "stray/spectrum_io.h"

/* eq. 2.1 for one source spectrum through the sensor's response. */
static int source_flux(const char *source, const struct stray_spectrum *qe,
		       double *flux, struct stray_error *err)
{
	struct stray_spectrum_data d;
	int rc = stray_spectrum_load(source, &d, err);

	if (rc != STRAY_OK)
		return rc;
	rc = stray_photon_flux(&d.s, qe, flux, err);
	stray_spectrum_data_free(&d);
	return rc;
}

int stray_reference_fluxes(const struct stray_sensor *s,
			   struct stray_fluxes *out, struct stray_error *err)
{
	struct stray_spectrum_data qe;
	int rc = stray_sensor_check(s, err);

	if (rc != STRAY_OK)
		return rc;
	rc = stray_spectrum_load(s->qe, &qe, err);
	if (rc != STRAY_OK)
		return rc;
	rc = source_flux(s->sun, &qe.s, &out->sun, err);
	if (rc == STRAY_OK)
		rc = source_flux(s->vega, &qe.s, &out->vega, err);
	stray_spectrum_data_free(&qe);
	if (rc != STRAY_OK)
		return rc;
	if (!(out->vega > 0.0))
		return stray_error_set(err, STRAY_EINVAL, "vega",
			"Vega gives no flux in this passband");
	/* eq. 2.2: Vega at vega_mag fixes F_0; every magnitude follows. */
	out->zero_mag = stray_zero_mag_flux(out->vega, s->vega_mag);
	out->moon = stray_mag_to_flux(out->zero_mag, s->moon_mag);
	out->drs = stray_mag_to_flux(out->zero_mag, s->drs_mag);
	out->sun_mag = stray_flux_to_mag(out->zero_mag, out->sun);
	return STRAY_OK;
}
