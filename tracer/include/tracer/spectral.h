/*
 * spectral.h - coatings whose reflectance changes with wavelength (issue
 * 17 item 5; scene files' "reflectance_table", tracer/scene.h).  Each
 * photon keeps its wavelength through all its bounces, so a path that
 * scattered on groups g_1..g_k weighs <prod_v rho_gv(l)> over the band
 * (source spectrum x detector response, in photons, eq. 2.1), not the
 * product of band means.  The geometry does not depend on wavelength
 * (Lambertian, ABg shape, mirror), so the trace runs once at grey
 * reflectances with its path records (tracer/paths.h: contribution /
 * prod rho per group sequence) and the per-order powers are re-weighted
 * exactly from them afterwards.
 */
#ifndef TRACER_SPECTRAL_H
#define TRACER_SPECTRAL_H

#include <stddef.h>

#include "stray/error.h"
#include "tracer/integrator.h"
#include "tracer/scene.h"

#define TRACER_BAND_MAX 128
#define TRACER_BAND_SOURCE "builtin:sun_am0_astm_e490"
#define TRACER_BAND_RESPONSE "builtin:qe_mt9p031_approx"

struct tracer_band {
	size_t n;
	double nm[TRACER_BAND_MAX], w[TRACER_BAND_MAX];	/* w sums to 1 */
};

/* Photon weights of source x response on a 10 nm grid from 300 nm
 * (NULL: the defaults above); errors name the file. */
int tracer_band_load(const char *source, const char *response,
		     struct tracer_band *b, struct stray_error *err);

/* True when some group has a reflectance table. */
int tracer_scene_spectral(const struct tracer_scene *s);

/* The table's reflectance at a wavelength. */
double tracer_rho_table_at(const struct tracer_rho_table *t, double nm);

/* Re-weight a trace of s made with record_paths: every batch's power of
 * scatter order o (1, 2, 3+) at each angle x (band-weighted sum /
 * grey sum) of that angle's and order's recorded paths.  Direct light
 * is unchanged.  Sigma keeps its relative size (an approximation). */
int tracer_result_apply_band(struct tracer_result *r,
			     const struct tracer_scene *s,
			     const struct tracer_band *b,
			     struct stray_error *err);

#endif /* TRACER_SPECTRAL_H */
