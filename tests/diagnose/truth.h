/*
 * truth.h - the hidden-effect generator of the diagnose tests: a
 * "measured" attenuation curve from the tracer with its own seed and
 * path count, one or more effects the diagnosis is not told about,
 * realistic measurement noise and a measurement floor.  Kept apart from
 * the diagnose/ library: it shares no code with the analysis.
 */
#ifndef STRAY_TESTS_DIAG_TRUTH_H
#define STRAY_TESTS_DIAG_TRUTH_H

#include <stddef.h>
#include <stdint.h>

#define TRUTH_SETS_MAX 16

struct truth_config {
	const char *scene;		/* NULL: ref4; else a scene file */
	const double *theta_deg;	/* logged angles, 0 first */
	size_t n;
	const char *sets[TRUTH_SETS_MAX];	/* hidden scene changes */
	int n_sets;
	double abg_g;			/* > 0: coating scatters ABg, B 0.01 */
	double pivot_mm;		/* rotation centre behind the aperture */
	double angle_offset_deg;	/* true angle = logged + offset */
	double floor;			/* additive background */
	double leak_level, leak_lo_deg, leak_hi_deg;	/* 0: none */
	double dip_factor, dip_lo_deg, dip_hi_deg;	/* 0: none */
	double beam_half_deg;		/* > 0: divergent beam, a uniform
					 * disk of directions (issue 17) */
	double beam_gauss_deg;		/* > 0: its intensity falls off as
					 * exp(-2 r^2 / w^2) inside it */
	double band_rho_blue, band_rho_red, band_split_nm;	/* > 0: a
					 * two-band coating over the Sun x QE
					 * band (issue 17): rho_blue below
					 * split, rho_red above */
	const char *group;		/* a surface group's reflectance */
	double group_factor;		/*   times this (0: none) */
	const char *lens;		/* lens table (system curve), or NULL */
	double rel_noise;		/* photometer noise, relative */
	double floor_sigma;		/* measurement floor, absolute */
	uint64_t seed, n_paths;
	uint64_t noise_seed;
};

/* Reasonable defaults: 3 % noise, floor 1e-7, 1e6 paths, seed 4242. */
void truth_defaults(struct truth_config *c, const double *theta, size_t n);

/* The two-band coating's band moments <rho^k>, k = 0..kmax (<= 7), over
 * the truth's own Sun x QE photon weights; 0 on success. */
int truth_band_moments(const struct truth_config *c, double *m, int kmax);

/* Write the measured curve CSV (theta_deg, alpha, sigma); 0 on success. */
int truth_write(const struct truth_config *c, const char *path);

#endif /* STRAY_TESTS_DIAG_TRUTH_H */
