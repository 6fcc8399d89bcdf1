/*
 * sensor.h - the numbers that describe a star-tracker sensor for the FDR
 * model (thesis §2.2-2.3).  Freestanding; the built-in `st16-like` sensor
 * is shared/reference/ref4-baffle.md's table, JSON loading is in
 * sensor_io.h.
 */
#ifndef STRAY_SENSOR_H
#define STRAY_SENSOR_H

#include "stray/error.h"
#include "stray/fdr.h"

#define STRAY_NAME_MAX 64
#define STRAY_PATH_MAX 512

/* Detector size limits (docs/limits.md): whole pixels, at most 65536 a
 * side and 1e8 in all (frames and maps allocate several bytes per pixel;
 * 1e10 pixels asked for 2^63 bytes). */
#define STRAY_SENSOR_SIDE_MAX 65536.0
#define STRAY_SENSOR_PIXELS_MAX 1e8

struct stray_sensor {
	char name[STRAY_NAME_MAX];
	double pixels_x, pixels_y;	/* n_tot = pixels_x * pixels_y */
	double pixel_pitch_um;		/* A_px = pitch^2 */
	double t_exp_s;			/* nominal exposure */
	double aperture_diameter_mm;	/* A_cs = pi d^2 / 4 */
	double star_window_px;		/* n_pps */
	double drs_mag;			/* designed reference star magnitude */
	double pr_drs;			/* DRS detection probability */
	double fdr_tolerated;		/* tolerated false stars per image */
	double fov_half_deg;		/* field-of-view half-angle */
	double read_noise_e;		/* extended model: e- rms */
	double dark_current_e_s;	/* extended model: e-/s */
	double vega_mag;		/* Vega's magnitude (0.03, §2.1) */
	double moon_mag;		/* full-Moon magnitude (-12.6, §5.1) */
	/* Spectra: "builtin:NAME" or a CSV path (resolved by the loader). */
	char qe[STRAY_PATH_MAX];
	char sun[STRAY_PATH_MAX];
	char vega[STRAY_PATH_MAX];
	/* The tracker's star detector (stray/detector.h): a name, "" for
	 * the thesis's; its k for tetra3 (0: the default 3). */
	char detector[16];
	double detector_sigma;
	/* Stars a solution needs in the field (0: the default 4). */
	double min_stars;
};

/*
 * How a curve alpha(theta) meets eq. 2.3 (docs/normalisation.md).  The
 * curves the toolkit makes are power ratios P(theta)/P(0) (eq. 3.11-3.12,
 * a trace): the on-axis beam fills the collecting area A_cs, so spread
 * over the detector the photons per pixel are alpha F t A_cs / n_tot =
 * alpha F t A_px k_px.  The thesis reads alpha as a per-pixel ratio.
 */
enum stray_normalisation {
	STRAY_NORM_CONSISTENT = 0,	/* k_px = A_cs / (n_tot A_px) */
	STRAY_NORM_THESIS = 1		/* k_px = 1, eq. 2.3 as printed */
};

/* "consistent" or "thesis". */
const char *stray_normalisation_name(enum stray_normalisation n);

/*
 * The per-pixel factor k_px of eq. 2.3 for a sensor: A_cs / (n_tot A_px)
 * with A_cs = pi d^2 / 4 (eq. 2.12), n_tot = pixels_x pixels_y and
 * A_px = pitch^2 (5.44 for st16-like); 1 for STRAY_NORM_THESIS.
 */
double stray_sensor_k_px(const struct stray_sensor *s,
			 enum stray_normalisation n);

/* The built-in reference sensor `st16-like`. */
const struct stray_sensor *stray_sensor_st16_like(void);

/* Every number finite and in its domain; STRAY_EINVAL names the field. */
int stray_sensor_check(const struct stray_sensor *s, struct stray_error *err);

/*
 * Fill an FDR model (thesis defaults: Gaussian, uniform, no detector
 * noise) from a sensor and the photon fluxes of source and DRS, with the
 * consistent normalisation (k_px = stray_sensor_k_px(s, CONSISTENT); set
 * m->k_px for another).
 */
void stray_sensor_fdr_model(const struct stray_sensor *s, double f_src,
			    double f_drs, struct stray_fdr_model *m);

#endif /* STRAY_SENSOR_H */
