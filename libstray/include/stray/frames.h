/*
 * frames.h - rendered detector frames (issue 13 item 3): the stray-light
 * background of eq. 2.3 with the per-pixel normalisation k_px, a star
 * field, dark current, read noise, Poisson shot noise, bias, 12-bit
 * quantisation and saturation.  Hosted layer (libstray/frames), but no
 * heap and no stdio: the caller owns every buffer.  Random numbers come
 * from one splitmix64 stream per (seed, frame), so a frame is reproducible
 * bit for bit.
 *
 * This is the *truth* generator of the frame validation: the analysis
 * (detector, model comparison) lives elsewhere and is told only what a
 * real instrument team would know (bias, gain, read noise, the curve).
 */
#ifndef STRAY_FRAMES_H
#define STRAY_FRAMES_H

#include <stddef.h>
#include <stdint.h>

/* Camera defaults, mirroring the lab simulator rig/sim/vlab.c (MT9P031-
 * class, 12-bit ADC): gain 2 e-/DN, bias 100 DN, saturation 4095 DN. */
#define STRAY_FRAMES_GAIN_E_PER_DN 2.0
#define STRAY_FRAMES_BIAS_DN 100.0
#define STRAY_FRAMES_SAT_DN 4095
/* Star PSF: a Gaussian of sigma = window radius / 4 (1.5 px for the
 * 13 px st16-like window), so the n_pps window holds > 99.9 % of a star's
 * photons, as eq. 2.12 assumes. */
#define STRAY_FRAMES_PSF_PER_RADIUS 0.25

struct stray_star {
	double x, y;		/* position on the rendered frame, px (pixel
				 * centres at integer + 0.5) */
	double mag;		/* magnitude in the sensor's band (eq. 2.2) */
	double photons_e;	/* F(m) t_exp A_cs, QE included (eq. 2.12) */
};

struct stray_frame_cfg {
	int cols, rows;			/* rendered size, px */
	int col0, row0;			/* detector pixel of the first one */
	double stray_e;			/* mean stray e-/px: k_px alpha F t A_px */
	const float *weight;		/* rows*cols relative stray weights of
					 * mean 1 (a focal map), NULL: uniform */
	double dark_e;			/* dark current e-/px over t_exp */
	double read_noise_e;		/* e- rms per pixel */
	double gain_e_per_dn;
	double bias_dn;
	int sat_dn;
	double psf_sigma_px;
	/* Truth-only effects (hidden-effect tests; 0 in `stray frames`). */
	double gradient;		/* stray x (1 + g (2 col/cols - 1)) */
	double hot_frac;		/* fraction of hot pixels (fixed places) */
	double hot_e;			/* extra e- of a hot pixel */
};

/* The synthetic star field: counts N(<m) per square degree. */
struct stray_star_field {
	double fov_deg2;		/* solid angle of the rendered frame */
	double mag_min, mag_max;	/* magnitudes drawn in [min, max] */
	double f0_e;			/* F_0 t_exp A_cs: e- of an m = 0 star */
};

/* Defaults for a frame of cols x rows px (camera of vlab.c, no stray). */
void stray_frame_cfg_defaults(struct stray_frame_cfg *c, int cols, int rows);

/*
 * Expected number of stars brighter than m per square degree, averaged
 * over the sky: N(<m) = 0.121 10^(0.44 (m - 6)).  Calibrated on the Yale
 * Bright Star Catalogue (about 9100 stars to V = 6.5 over 41253 deg^2)
 * with the slope d log N / dm = 0.44 of the all-sky average star counts
 * at 6-10 mag (Bahcall & Soneira 1980, ApJS 44, 73).  Not a catalogue.
 */
double stray_star_counts_per_deg2(double mag);

/*
 * Draw a synthetic star field on a cols x rows frame: a Poisson number of
 * stars with uniform positions and magnitudes from N(<m).  Writes at most
 * max stars (a fair subset when the draw exceeds it); *n gets the count.
 */
void stray_star_field_draw(const struct stray_star_field *f, int cols,
			   int rows, uint64_t seed, struct stray_star *stars,
			   size_t max, size_t *n);

/*
 * The expected electrons of every pixel (stray light, dark current, stars
 * through the pixel-integrated Gaussian PSF, hot pixels) into expect_e.
 */
void stray_frame_expect(const struct stray_frame_cfg *c,
			const struct stray_star *stars, size_t n_stars,
			float *expect_e);

/*
 * One frame in DN: Poisson(expect_e) + N(0, read noise), over the gain,
 * plus bias, rounded, clipped to [0, sat_dn].  Deterministic in seed.
 */
void stray_frame_sample(const struct stray_frame_cfg *c,
			const float *expect_e, uint64_t seed, uint16_t *dn);

/* A splitmix64 seed for frame number i of a run seeded with seed. */
uint64_t stray_frame_seed(uint64_t seed, uint64_t i);

#endif /* STRAY_FRAMES_H */
