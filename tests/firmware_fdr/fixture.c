/*
 * fixture.c - the reference curve and table of the firmware_fdr tests.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fdrfw/table_build.h"
#include "fixture.h"
#include "stray/sensor.h"

#define N_CURVE 86

static double theta[N_CURVE], alpha[N_CURVE];
static struct stray_curve_view view;
static struct stray_fluxes fluxes;
static int ready;

/* log10 alpha of the shape described in fixture.h. */
static double shape(double th)
{
	double l;

	if (th <= 10.0)
		l = log10(cos(th * 0.017453292519943295));
	else if (th <= 27.0)	/* direct light vignetted by the vanes */
		l = -3.0 * (th - 10.0) / 17.0;
	else
		l = -3.0 - 6.0 * (1.0 - exp(-(th - 27.0) / 8.0));
	if (th > 46.0 && th < 56.0)	/* the lit bevels */
		l += 1.2 * sin((th - 46.0) * 0.3141592653589793);
	return l;
}

static void setup(void)
{
	struct stray_error err;
	int i;

	if (ready)
		return;
	for (i = 0; i < N_CURVE; i++) {
		theta[i] = i;
		alpha[i] = pow(10.0, shape(i));
	}
	view.n = N_CURVE;
	view.theta_deg = theta;
	view.alpha = alpha;
	view.sigma = NULL;
	stray_error_clear(&err);
	assert_int_equal(stray_reference_fluxes(stray_sensor_st16_like(),
						&fluxes, &err), 0);
	ready = 1;
}

const struct stray_curve_view *fixture_curve(void)
{
	setup();
	return &view;
}

const struct stray_fluxes *fixture_fluxes(void)
{
	setup();
	return &fluxes;
}

void fixture_table(struct fdrfw_table *t)
{
	struct fdrfw_build_params p = {
		.f_sun_ph_s_m2 = 0, .rate = 0,
		.hysteresis_deg = FDRFW_BUILD_HYSTERESIS_DEG,
		.earth_albedo = FDRFW_BUILD_ALBEDO,
	};
	struct stray_error err;

	setup();
	p.f_sun_ph_s_m2 = fluxes.sun;
	p.f_moon_full_ph_s_m2 = fluxes.moon;
	p.f_drs_ph_s_m2 = fluxes.drs;
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_build(&view, stray_sensor_st16_like(), &p,
					   t, &err), 0);
}
