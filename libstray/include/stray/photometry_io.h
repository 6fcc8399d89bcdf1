/*
 * photometry_io.h - the reference fluxes of a sensor (thesis table 2.1):
 * its spectra loaded and integrated through eq. 2.1-2.2 (hosted).
 */
#ifndef STRAY_PHOTOMETRY_IO_H
#define STRAY_PHOTOMETRY_IO_H

#include "stray/error.h"
#include "stray/sensor.h"

/* Photon fluxes in the sensor's passband, ph s^-1 m^-2. */
struct stray_fluxes {
	double sun;
	double moon;		/* full Moon at the sensor's moon_mag */
	double zero_mag;	/* F_0: Vega fixed at vega_mag */
	double vega;
	double drs;		/* designed reference star at drs_mag */
	double sun_mag;		/* the Sun's magnitude in this passband */
};

int stray_reference_fluxes(const struct stray_sensor *s,
			   struct stray_fluxes *out, struct stray_error *err);

#endif /* STRAY_PHOTOMETRY_IO_H */
