/*
 * sky_coverage.h - the tracker's requirement rather than one proxy
 * (issue 28 item 3): the fraction of the sky where at least N stars stay
 * detectable, a star detectable when it is brighter than the detector's
 * limiting magnitude (found with Pr_drs, stray/detector.h) at the stray
 * level.  Over the synthetic catalogue (stray/catalogue.h: no real one is
 * installed; every output says so), through the sensor's ideal camera.
 */
#ifndef STRAY_SKY_COVERAGE_H
#define STRAY_SKY_COVERAGE_H

#include "stray/error.h"
#include "stray/sensor.h"

#define SKY_COVERAGE_DIRS 400	/* boresights, a Fibonacci lattice */
#define SKY_COVERAGE_SOURCE "synthetic catalogue (stray/catalogue.h)"

/* Fraction of the boresights whose detector holds >= n_min stars
 * brighter than mag_lim. */
int sky_coverage(const struct stray_sensor *s, double mag_lim, int n_min,
		 double *frac, struct stray_error *err);

#endif /* STRAY_SKY_COVERAGE_H */
