/*
 * flightcheck.h - the analysis of `stray flightcheck` (issue 18, thesis
 * §4.3): flight frames -> Sun offset angle, robust background, catalogue
 * stars matched through the attitude, the absolute calibration from
 * those stars, the measured alpha_px(theta) and its scale against the
 * predicted curve.  Knows only what a tracker team knows: the camera
 * (bias, gain, dark current, read noise), the sensor (optics, passband
 * photometry), the catalogue, time and attitude.  Linked by the command,
 * its test (tests/flightcheck) and its bench.
 */
#ifndef STRAY_MISSION_FLIGHTCHECK_H
#define STRAY_MISSION_FLIGHTCHECK_H

#include <stddef.h>
#include <stdint.h>

#include "stray/catalogue.h"
#include "stray/colour.h"
#include "stray/starcat.h"

#define FC_TILE_PX 64		/* background tiles */
#define FC_MAG_CAL 8.5		/* calibration stars: brighter than this */
#define FC_APERTURE_PX 6.0
#define FC_BG_SYS_DN 0.05	/* background systematic floor, DN */	/* the star window's radius (r of n_pps) */

struct fc_cfg {
	int cols, rows;		/* frame size */
	double f_px, cx, cy;	/* ideal camera: focal length in px, axis */
	double t_exp_s, gain_e_per_dn, bias_dn, dark_e, sat_dn;
	double f0_e;		/* photo-e- of an m = 0 star: F_0 t A_cs (eq. 2.2, 2.12) */
	double sun_e;		/* F_sun t_exp A_px: photo-e- per pixel per unit alpha_px (eq. 2.3) */
	uint64_t cat_seed;	/* the synthetic catalogue (stray/catalogue.h) */
	const struct stray_starcat *starcat;	/* a real one, or NULL */
	const struct stray_colour *colour;	/* its B-V to the passband */
	double search_px;	/* first-pass search half-width around a prediction */
};

/* Buffers of one analysis thread (fc_work_alloc / fc_work_free). */
struct fc_work {
	struct stray_cat_star *cat;
	size_t cat_max;
	struct stray_star *pred;
	size_t pred_max;
	float *tile_med;	/* per tile */
	uint16_t *sample;	/* one tile's samples */
	uint32_t *hist;		/* 4096 DN bins */
	double *mx, *my;	/* matched centroids */
};

struct fc_frame {
	double t_tt;		/* TT s since J2000 */
	double theta_deg;	/* Sun offset angle of the boresight */
	double bg_dn, bg_sigma_dn;	/* mean background (plane), its error */
	double noise_dn;	/* pixel noise (tile MAD) */
	double grad_dn_per_px, grad_dir_deg;	/* plane slope, direction (0 = +x) */
	int n_tiles_used, n_pred, n_match, n_cal;
	int n_sure, n_sure_found;	/* predicted bright enough that they
					 * must be found (FC_SURE_SNR), found */
	double dx_px, dy_px, rot_deg, resid_px;	/* refinement on the matches */
	double cal_sw, cal_swr, cal_swr2;	/* sums for DN per photo-e- */
	double t_exp_s;		/* its EXPTIME; 0: the cfg's (the sensor's) */
	double gain_e_per_dn, bias_dn;	/* its GAIN, BIAS; 0: the cfg's */
	double moon_deg;	/* Moon offset angle of the boresight */
	double limb_deg;	/* Earth limb's (negative: Earth in the
				 * boresight's way); NAN without an orbit */
	int screened;		/* 1: Moon or Earth too near, not fitted */
};

int fc_work_alloc(struct fc_work *w, const struct fc_cfg *c);
void fc_work_free(struct fc_work *w);

/* The Sun offset angle [deg] of the boresight (+z of the head) at t_tt
 * with attitude q_ib (stray/aem.h convention). */
double fc_sun_angle_deg(const double q_ib[4], double t_tt);

/* The background (mission/flightcheck_bg.c): a grouped median per tile, a
 * plane fitted to the tiles with two 3-sigma rejections; o's background,
 * noise and gradient fields. */
void fc_background(const struct fc_cfg *c, struct fc_work *w,
		   const uint16_t *dn, double plane[3], struct fc_frame *o);

/* One frame (the per-frame step): background, stars, calibration sums. */
void fc_frame_analyse(const struct fc_cfg *c, struct fc_work *w,
		      const uint16_t *dn, const double q_ib[4], double t_tt,
		      struct fc_frame *out);

/* The flight curve and its comparison with the prediction. */
struct fc_point {
	double theta_deg, alpha_px, sigma;	/* measured, absolute */
	double model;		/* predicted alpha_sys(theta), relative */
};

struct fc_summary {
	double dn_per_e, dn_per_e_sigma;	/* star calibration */
	double cal_chi2_dof;
	int n_cal;
	double scale, scale_sigma_stat, scale_sigma;	/* alpha_px / alpha_model */
	double chi2_dof;	/* of the scaled model: the shape test */
	double k_px_model, scale_over_kpx, scale_over_kpx_sigma;
	int n_pred, n_match;	/* over all frames */
	int n_screened;		/* frames left out of the scale fit */
	int n_frames;
	int n_sure, n_sure_found;
	double match_frac;	/* n_sure_found / n_sure */
	double resid_px;	/* rms plate residual over all matches */
};

/* The honest verdict (issue 24): a frame set is calibrated only with at
 * least FC_MIN_CAL calibrators, FC_MIN_MATCH of its predicted stars
 * found and a plate residual under FC_MAX_RESID_PX (docs/limits.md). */
#define FC_MIN_CAL 3
#define FC_SURE_SNR 40.0	/* a star's predicted DN over the pixel noise */
#define FC_MIN_MATCH 0.3
#define FC_MAX_RESID_PX 1.5
/* 0 when s passes; else 1 and why (one line) says which rule failed. */
int fc_verdict(const struct fc_summary *s, char *why, size_t n);

/* Calibration over all frames, alpha_px per frame (pts[i].model set by
 * the caller), and the best scale; points with no light are kept. */
void fc_summarise(const struct fc_cfg *c, const struct fc_frame *f,
		  size_t n, double k_px_model, struct fc_point *pts,
		  struct fc_summary *s);



struct stray_sensor;
struct stray_fluxes;
/* The analysis configuration of a cols x rows frame whose first pixel is
 * detector (col0, row0): the ideal camera of stray_sensor_pixel_deg, the
 * camera of stray/frames.h, the fluxes of the sensor's passband. */
void fc_cfg_init(struct fc_cfg *c, const struct stray_sensor *s,
		 const struct stray_fluxes *fl, int cols, int rows, int col0,
		 int row0);

/* c for a frame exposed t_exp_s (> 0): the star, dark and Sun counts
 * of c (at c->t_exp_s) scaled to it. */
void fc_cfg_exposure(const struct fc_cfg *c, double t_exp_s,
		     struct fc_cfg *out);
#endif /* STRAY_MISSION_FLIGHTCHECK_H */
