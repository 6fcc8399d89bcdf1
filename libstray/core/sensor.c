/*
 * sensor.c - the built-in reference sensor and the bridge from a sensor to
 * the FDR model (thesis §2.2-2.3).  Freestanding.
 */
#include <math.h>

#include "stray/config.h"
#include "stray/sensor.h"

#define PI 3.14159265358979323846

/* shared/reference/ref4-baffle.md, "Reference sensor st16-like". */
static const struct stray_sensor st16_like = {
	.name = "st16-like",
	.pixels_x = 2592.0,
	.pixels_y = 1944.0,
	.pixel_pitch_um = 2.2,
	.t_exp_s = 0.1,
	.aperture_diameter_mm = 13.0,
	.star_window_px = 113.0,	/* a 12 px diameter disc */
	.drs_mag = 5.75,
	.pr_drs = 0.95,
	.fdr_tolerated = 5.0,
	.fov_half_deg = 10.0,
	.read_noise_e = 3.0,
	.dark_current_e_s = 4.0,
	.vega_mag = 0.03,
	.moon_mag = -12.6,
	.qe = "builtin:qe_mt9p031_approx",
	.sun = "builtin:sun_am0_astm_e490",
	.vega = "builtin:vega_calspec_alpha_lyr_stis_011",
};

const struct stray_sensor *stray_sensor_st16_like(void)
{
	return &st16_like;
}

static int check_positive(double v, const char *field,
			  struct stray_error *err)
{
	if (!(isfinite(v) && v > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, field,
			STRAY_MSG("must be finite and > 0"), v);
	return STRAY_OK;
}

static int check_finite(double v, const char *field, struct stray_error *err)
{
	if (!isfinite(v))
		return stray_error_set_value(err, STRAY_EINVAL, field,
			STRAY_MSG("must be finite"), v);
	return STRAY_OK;
}

/* A whole number of pixels within the side limit (positive already):
 * frames, maps and windows are allocated and indexed by it. */
static int check_pixels(double v, const char *field, struct stray_error *err)
{
	if (!(v <= STRAY_SENSOR_SIDE_MAX))
		return stray_error_set_value(err, STRAY_EINVAL, field,
			STRAY_MSG("must be <= 65536 (docs/limits.md)"), v);
	if ((double)(long)v != v)
		return stray_error_set_value(err, STRAY_EINVAL, field,
			STRAY_MSG("must be a whole number of pixels"), v);
	return STRAY_OK;
}

int stray_sensor_check(const struct stray_sensor *s, struct stray_error *err)
{
	int rc;

	if ((rc = check_positive(s->pixels_x, "pixels_x", err)) ||
	    (rc = check_positive(s->pixels_y, "pixels_y", err)) ||
	    (rc = check_positive(s->pixel_pitch_um, "pixel_pitch_um", err)) ||
	    (rc = check_positive(s->t_exp_s, "t_exp_s", err)) ||
	    (rc = check_positive(s->aperture_diameter_mm,
				 "aperture_diameter_mm", err)) ||
	    (rc = check_positive(s->fdr_tolerated, "fdr_tolerated", err)) ||
	    (rc = check_finite(s->drs_mag, "drs_mag", err)) ||
	    (rc = check_finite(s->vega_mag, "vega_mag", err)) ||
	    (rc = check_finite(s->moon_mag, "moon_mag", err)))
		return rc;
	if ((rc = check_pixels(s->pixels_x, "pixels_x", err)) ||
	    (rc = check_pixels(s->pixels_y, "pixels_y", err)))
		return rc;
	if (!(s->pixels_x * s->pixels_y <= STRAY_SENSOR_PIXELS_MAX))
		return stray_error_set_value(err, STRAY_EINVAL, "pixels_y",
			STRAY_MSG("pixels_x * pixels_y must be <= 1e8 "
				  "(docs/limits.md)"), s->pixels_y);
	if (!(s->star_window_px >= 1.0 &&
	      s->star_window_px <= s->pixels_x * s->pixels_y))
		return stray_error_set_value(err, STRAY_EINVAL, "star_window_px",
			STRAY_MSG("must be >= 1 and <= the detector's pixels"),
			s->star_window_px);
	if (!(s->pr_drs > 0.0 && s->pr_drs < 1.0))
		return stray_error_set_value(err, STRAY_EINVAL, "pr_drs",
			STRAY_MSG("must lie strictly between 0 and 1"), s->pr_drs);
	if (!(s->fov_half_deg > 0.0 && s->fov_half_deg < 90.0))
		return stray_error_set_value(err, STRAY_EINVAL, "fov_half_deg",
			STRAY_MSG("must lie in (0, 90)"), s->fov_half_deg);
	if (!(isfinite(s->read_noise_e) && s->read_noise_e >= 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "read_noise_e",
			STRAY_MSG("must be finite and >= 0"), s->read_noise_e);
	if (!(isfinite(s->dark_current_e_s) && s->dark_current_e_s >= 0.0))
		return stray_error_set_value(err, STRAY_EINVAL,
			"dark_current_e_s", STRAY_MSG("must be finite and >= 0"),
			s->dark_current_e_s);
	/* 0 is "not given" (tetra3's default k = 3, stray/detector.h) */
	if (!(s->detector_sigma == 0.0 ||
	      (s->detector_sigma >= 0.5 && s->detector_sigma <= 20.0)))
		return stray_error_set_value(err, STRAY_EINVAL, "detector_sigma",
			STRAY_MSG("must lie in 0.5..20"), s->detector_sigma);
	if (!(s->min_stars == 0.0 || (s->min_stars >= 1.0 &&
	      s->min_stars <= 100.0 && s->min_stars == (int)s->min_stars)))
		return stray_error_set_value(err, STRAY_EINVAL, "min_stars",
			STRAY_MSG("must be a whole number in 1..100"),
			s->min_stars);
	return STRAY_OK;
}

/* A_px = pitch^2 (eq. 2.3) [m^2]. */
static double pixel_area_m2(const struct stray_sensor *s)
{
	double pitch_m = s->pixel_pitch_um * 1e-6;

	return pitch_m * pitch_m;
}

/* A_cs = pi d^2 / 4 (eq. 2.12) [m^2]. */
static double collecting_area_m2(const struct stray_sensor *s)
{
	double radius_m = 0.5 * s->aperture_diameter_mm * 1e-3;

	return PI * radius_m * radius_m;
}

const char *stray_normalisation_name(enum stray_normalisation n)
{
	return n == STRAY_NORM_THESIS ? "thesis" : "consistent";
}

double stray_sensor_k_px(const struct stray_sensor *s,
			 enum stray_normalisation n)
{
	if (n == STRAY_NORM_THESIS)
		return 1.0;
	/* eq. 2.3 with eq. 3.11-3.12's alpha: A_cs / A_det */
	return collecting_area_m2(s) /
	       (s->pixels_x * s->pixels_y * pixel_area_m2(s));
}

void stray_sensor_fdr_model(const struct stray_sensor *s, double f_src,
			    double f_drs, struct stray_fdr_model *m)
{
	m->f_src_ph_s_m2 = f_src;
	m->f_drs_ph_s_m2 = f_drs;
	m->t_exp_s = s->t_exp_s;
	m->a_px_m2 = pixel_area_m2(s);
	m->k_px = stray_sensor_k_px(s, STRAY_NORM_CONSISTENT);
	m->a_cs_m2 = collecting_area_m2(s);
	m->n_pps = s->star_window_px;
	m->n_tot = s->pixels_x * s->pixels_y;
	m->pr_drs = s->pr_drs;
	m->read_noise_e = 0.0;	/* thesis model: detector noise neglected */
	m->dark_current_e_s = 0.0;
	m->noise = STRAY_NOISE_GAUSS;
	m->map = 0;
}
