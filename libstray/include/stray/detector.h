/*
 * detector.h - named star detectors and both ways stray light blinds a
 * tracker with each (issue 28; ../shared/docs/method.md §2, §8).
 * Freestanding C99, no heap, every loop bounded.
 *
 * A detector has two failure modes under a background of I_px stray
 * photons per pixel (eq. 2.3):
 *   - false stars: noise crossing its threshold (eq. 2.17-2.18 and their
 *     extensions in fdr_field.h), per image;
 *   - lost stars: a real star of I photons (eq. 2.12) no longer crossing
 *     it, so the designed reference star (DRS) and the stars a solution
 *     needs go missing.
 * Detectors (thresholds set for a dark sky from the DRS, eq. 2.16, except
 * the k sigma one, which follows the frame):
 *   THESIS    eq. 2.18 as published: n_tot/n_pps independent windows; its
 *             lost-star model is eq. 2.16 with the background's variance.
 *   WINDOW    the n_pps disk window summed at every pixel against I_sdt,
 *             one star per connected region (fdr_field.h's sliding model);
 *             a star is found where any window near it clears I_sdt.
 *   THRESHOLD pixels above a fixed threshold (the DRS's min_px-th
 *             brightest pixel at Pr_drs), >= min_px 8-connected.
 *   TETRA3    tetra3 / cedar-solve's get_centroids_from_image defaults:
 *             local-mean background, threshold k times the frame's RMS,
 *             binary opening with the 3x3 cross, then blob areas >= min_px:
 *             constant-false-alarm, so the threshold rises with I_px.
 */
#ifndef STRAY_DETECTOR_H
#define STRAY_DETECTOR_H

#include "stray/fdr.h"
#include "stray/fdr_field.h"

enum stray_detector_kind {
	STRAY_DET_THESIS = 0,
	STRAY_DET_WINDOW = 1,
	STRAY_DET_THRESHOLD = 2,
	STRAY_DET_TETRA3 = 3
};
#define STRAY_DET_COUNT 4

/* Window positions near a star searched by the WINDOW model. */
#define STRAY_DET_POS_MAX 21

/* THRESHOLD's lost-star model (detector_blob.c): the 8-connected lattice
 * animals of 1..min_px-1 cells through a pixel (1 + 8 + 60 + 440 = 509
 * for min_px 5), each with its 8-neighbour perimeter; cells and perimeter
 * as codes (dy + 4) * 9 + dx + 4 about that pixel. */
#define STRAY_DET_BLOB_PX_MAX 5		/* min_px the table covers */
#define STRAY_DET_ANIMALS_MAX 512
#define STRAY_DET_PERIM_MAX 24
struct stray_det_animal {
	unsigned char n_cell, n_per;
	unsigned char cell[STRAY_DET_BLOB_PX_MAX - 1];
	unsigned char per[STRAY_DET_PERIM_MAX];
};

struct stray_detector {
	enum stray_detector_kind kind;
	stray_real sigma_k;		/* TETRA3: threshold in frame sigmas */
	unsigned min_px;		/* THRESHOLD, TETRA3: least blob area */
	stray_real psf_sigma_px;	/* Gaussian PSF sigma of a star */
	stray_real window_r_px;		/* disk window radius (n_pps) */
	/* Filled by stray_detector_setup from the model. */
	stray_real i_sdt_e;		/* THESIS, WINDOW: eq. 2.16 */
	stray_real pixel_t_e;		/* THRESHOLD: pixel threshold */
	struct stray_window_corr win;	/* WINDOW: neighbour overlaps */
	stray_real pos_rho;		/* WINDOW: mean overlap of positions */
	/* WINDOW, THRESHOLD: rms of the error of the detector's background
	 * estimate per pixel, in units of the mean stray level: the focal
	 * map's structure its estimator cannot follow (stray frames: the map
	 * against its 128 px tiles' bilinear, frames_mapterm.h).  0: none
	 * (uniform light, or a region map without places). */
	stray_real bg_resid_rel;
	/* THRESHOLD, min_px <= STRAY_DET_BLOB_PX_MAX: the animals smaller
	 * than min_px through a pixel (0: the Poisson-binomial rule). */
	unsigned n_animal;
	struct stray_det_animal animal[STRAY_DET_ANIMALS_MAX];
};

/* "thesis", "window", "threshold", "tetra3" (NULL outside the enum). */
const char *stray_detector_name(enum stray_detector_kind k);

/* The kind named by name; STRAY_EINVAL (field "detector") otherwise. */
int stray_detector_parse(const char *name, enum stray_detector_kind *k,
			 struct stray_error *err);

/*
 * Defaults for a window of n_pps pixels: radius round(sqrt(n_pps / pi)),
 * PSF sigma radius / 4 (the window holds > 99.9 % of a star, as eq. 2.12
 * assumes; stray frames renders the same), min_px 5 and k = 3 (tetra3's
 * minimum area, the sigma issue 28 measured cedar-solve at).
 */
void stray_detector_init(struct stray_detector *d,
			 enum stray_detector_kind kind, stray_real n_pps);

/* Check the parameters and derive the thresholds from the model. */
int stray_detector_setup(struct stray_detector *d,
			 const struct stray_fdr_model *m,
			 struct stray_error *err);

/* Variance of one pixel's count at attenuation alpha: I_px + read^2 +
 * dark t (the model's detector noise; zero for the bare thesis). */
stray_real stray_detector_pixel_var(const struct stray_fdr_model *m,
				    stray_real alpha);

/* ln false stars per image of m->n_tot pixels at alpha (map included,
 * and the background-error term: eq. R of detector.c). */
int stray_detector_log_false_rate(const struct stray_detector *d,
				  const struct stray_fdr_model *m,
				  stray_real alpha, stray_real *log_rate,
				  struct stray_error *err);

/*
 * Probability that a star of star_e photo-electrons at a uniformly random
 * place is detected at attenuation alpha (averaged over the map's regions
 * and over the star's place within a pixel).
 */
int stray_detector_star_prob(const struct stray_detector *d,
			     const struct stray_fdr_model *m, stray_real alpha,
			     stray_real star_e, stray_real *p,
			     struct stray_error *err);

/* The photons a star needs to be detected with probability pr at alpha
 * (the limiting magnitude's flux); STRAY_ERANGE beyond 1e12 e-. */
int stray_detector_limiting_e(const struct stray_detector *d,
			      const struct stray_fdr_model *m,
			      stray_real alpha, stray_real pr,
			      stray_real *star_e, struct stray_error *err);

enum stray_failure_mode {
	STRAY_FAIL_FALSE_STARS = 0,
	STRAY_FAIL_LOST_STARS = 1
};

/* "false_stars" or "lost_stars". */
const char *stray_failure_mode_name(enum stray_failure_mode f);

struct stray_detector_req {
	stray_real alpha_false;	/* false stars reach the tolerated rate;
				 * +inf: never (a k sigma detector) */
	stray_real alpha_lost;	/* the DRS's detection falls to pr_min;
				 * 0: not even in the dark */
	stray_real alpha_req;	/* the smaller: both requirements met */
	enum stray_failure_mode binding;
};

/*
 * The attenuation below which the detector sees at most `rate` false
 * stars per image and detects the DRS with probability >= pr_min.  The
 * THESIS detector is eq. 2.18 as published: its answer is the false-star
 * one (its I_sdt detects the DRS with exactly Pr_drs in the dark, so
 * alpha_lost is 0 for pr_min = Pr_drs), alpha_lost is reported beside it.
 * STRAY_ERANGE when neither mode is reached; STRAY_EINVAL (pr_drs) when
 * the DRS is missed with pr_min even in the dark.
 */
int stray_detector_alpha_required(const struct stray_detector *d,
				  const struct stray_fdr_model *m,
				  stray_real rate, stray_real pr_min,
				  struct stray_detector_req *r,
				  struct stray_error *err);

/* Shared by detector.c and detector_star.c. */
/* Fraction of a star's photons (Gaussian PSF of sigma s, pixel-
 * integrated) in pixel (i, j), the star at (ox, oy) from pixel (0, 0)'s
 * centre. */
stray_real stray_detector_psf_pixel(stray_real s, stray_real ox,
				    stray_real oy, int i, int j);
/* The WINDOW model's positions near a star: offsets of pixel centres from
 * the star's pixel within sqrt(5) px; returns their number. */
unsigned stray_detector_positions(int dx[STRAY_DET_POS_MAX],
				  int dy[STRAY_DET_POS_MAX]);
/* THRESHOLD's animals for d->min_px (n_animal 0 past
 * STRAY_DET_BLOB_PX_MAX); called by stray_detector_setup. */
int stray_detector_blob_setup(struct stray_detector *d,
			      struct stray_error *err);
/* THRESHOLD: the chance that the 8-connected component of pixels above
 * d->pixel_t_e through one of the four pixels nearest a star of star e-
 * at (ox, oy) in [0, 1/2)^2 from pixel (0, 0)'s centre has >= min_px
 * pixels, under background variance b. */
stray_real stray_detector_blob_prob(const struct stray_detector *d,
				    stray_real b, stray_real star,
				    stray_real ox, stray_real oy, stray_real t);
/* The background-error term: STRAY_DET_RESID_NODES Gauss-Hermite nodes
 * (z, weight) of N(0, 1), the error at node k being z_k bg_resid_rel
 * I_px(alpha); n = 1 (z 0, weight 1) when bg_resid_rel is 0 or the
 * detector follows the frame (THESIS, TETRA3). */
#define STRAY_DET_RESID_NODES 7
unsigned stray_detector_resid_nodes(const struct stray_detector *d,
				    stray_real z[STRAY_DET_RESID_NODES],
				    stray_real w[STRAY_DET_RESID_NODES]);
/* TETRA3's threshold above the background at alpha, e-. */
stray_real stray_detector_tetra3_threshold(const struct stray_detector *d,
					   const struct stray_fdr_model *m,
					   stray_real alpha);

#endif /* STRAY_DETECTOR_H */
