/*
 * frames_fixture.h - shared setup of the frame tests: the st16-like model
 * for a small window (what the analysis knows) and a truth frame rendered
 * by the library with effects the analysis is not told about.  Truth and
 * analysis meet only through the DN frame and the star list.
 */
#ifndef STRAY_TESTS_FRAMES_FIXTURE_H
#define STRAY_TESTS_FRAMES_FIXTURE_H

#include <stdlib.h>

#include "frames/frames_run.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

/* The nominal model at stray level alpha_eff = k_px alpha (uniform). */
static void fixture_model(struct frames_model *fm, double alpha_eff, int w)
{
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_fluxes f;
	struct stray_error err;

	stray_error_clear(&err);
	assert_int_equal(stray_reference_fluxes(s, &f, &err), STRAY_OK);
	assert_int_equal(frames_model_init(fm, s, f.sun, f.drs, 1.0, alpha_eff,
					   w, w, NULL, &err), STRAY_OK);
}

#endif /* STRAY_TESTS_FRAMES_FIXTURE_H */
