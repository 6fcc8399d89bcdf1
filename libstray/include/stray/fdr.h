/*
 * fdr.h - the false-detection-rate model (thesis §2.3, eq. 2.3-2.18).
 *
 * Freestanding C99, no heap: the flight module links this file.  The model
 * turns a system attenuation alpha_sys into the expected number of false
 * stars per image, and inverts it into the attenuation required for a
 * tolerated rate.  The defaults reproduce the thesis exactly (Gaussian shot
 * noise, uniform stray light, no detector noise); the extensions are
 * switched on by fields that default to zero.  Numbers are stray_real
 * (config.h): double, or float in flight builds.
 */
#ifndef STRAY_FDR_H
#define STRAY_FDR_H

#include "stray/config.h"
#include "stray/error.h"

enum stray_noise_model {
	STRAY_NOISE_GAUSS = 0,	/* eq. 2.4-2.10: Poisson ~ Gaussian */
	STRAY_NOISE_POISSON = 1	/* exact Poisson tails (low counts) */
};

/*
 * A non-uniform stray-light map: the detector split into regions, region r
 * covering fraction[r] of the pixels at rel_alpha[r] times the mean
 * attenuation.  The thesis assumes one region (uniform light, §2.3); a map
 * replaces that simplification.  rel_alpha is normalised internally so
 * that sum(fraction * rel_alpha) = 1, i.e. alpha stays the mean.
 */
struct stray_region_map {
	unsigned n;
	stray_real fraction[STRAY_MAP_REGIONS_MAX];
	stray_real rel_alpha[STRAY_MAP_REGIONS_MAX];
};

struct stray_fdr_model {
	stray_real f_src_ph_s_m2;	/* F_src: source flux (eq. 2.3) */
	stray_real f_drs_ph_s_m2;	/* F_drs: reference-star flux (2.12) */
	stray_real t_exp_s;		/* exposure time t_exp */
	stray_real a_px_m2;		/* pixel area A_px (eq. 2.3) */
	/* Per-pixel factor of eq. 2.3: I_px = alpha F t A_px k_px.  A power-
	 * ratio curve (eq. 3.11-3.12, a trace) is normalised by the on-axis
	 * beam over A_cs, so k_px = A_cs / (n_tot A_px); the thesis uses 1
	 * (stray_sensor_k_px, docs/normalisation.md). */
	stray_real k_px;
	stray_real a_cs_m2;		/* collecting area A_cs (eq. 2.12) */
	stray_real n_pps;		/* pixels per star window (eq. 2.7) */
	stray_real n_tot;		/* pixels on the detector (eq. 2.18) */
	stray_real pr_drs;		/* DRS detection prob. (eq. 2.16) */
	/* Extensions beyond the thesis; zero/NULL reproduces it. */
	stray_real read_noise_e;	/* e- rms per pixel per frame */
	stray_real dark_current_e_s;	/* e- per pixel per s */
	enum stray_noise_model noise;
	const struct stray_region_map *map;	/* NULL: uniform light */
};

/* Check every field of a model; STRAY_EINVAL names the bad one. */
int stray_fdr_model_check(const struct stray_fdr_model *m,
			  struct stray_error *err);

/* eq. 2.3: expected stray photons in one pixel at attenuation alpha,
 * alpha F_src t_exp A_px k_px. */
stray_real stray_fdr_pixel_photons(const struct stray_fdr_model *m,
				   stray_real alpha);

/* eq. 2.12: expected photons of the designed reference star. */
stray_real stray_fdr_drs_photons(const struct stray_fdr_model *m);

/* eq. 2.16: star-detection threshold I_sdt (photo-electrons per window). */
int stray_fdr_threshold(const struct stray_fdr_model *m, stray_real *i_sdt,
			struct stray_error *err);

/*
 * eq. 2.16 in the Gaussian model for a known z = Q^-1(Pr_drs) (from
 * stray_gauss_q_inv): I_sdt = I_drs + z sqrt(I_drs + b), no root search.
 * z depends on Pr_drs alone, so a caller whose exposure changes solves it
 * once and keeps it (stray_fdr_threshold uses this same expression).
 */
stray_real stray_fdr_threshold_gauss(const struct stray_fdr_model *m,
				     stray_real z_drs);

/*
 * eq. 2.17: ln Pr_fd, the probability that one uniformly lit window at
 * attenuation alpha exceeds the threshold i_sdt (from stray_fdr_threshold).
 */
int stray_fdr_log_pr_fd(const struct stray_fdr_model *m, stray_real alpha,
			stray_real i_sdt, stray_real *log_pr_fd,
			struct stray_error *err);

/* sum fraction * rel_alpha of a map (the divisor of its rel_alpha);
 * STRAY_EINVAL when the map carries no light. */
int stray_region_map_norm(const struct stray_region_map *map,
			  stray_real *norm, struct stray_error *err);

/* eq. 2.18: ln FDR, false detections per image, summed over the map. */
int stray_fdr_log_rate(const struct stray_fdr_model *m, stray_real alpha,
		       stray_real i_sdt, stray_real *log_fdr,
		       struct stray_error *err);

/* eq. 2.18: FDR itself (0 where it underflows, see stray_fdr_log_rate). */
int stray_fdr_rate(const struct stray_fdr_model *m, stray_real alpha,
		   stray_real *fdr, struct stray_error *err);

/*
 * The attenuation alpha_req at which FDR = rate (fig. 2.7), by a bracketed
 * root search on ln FDR(ln alpha) over alpha in [1e-30, 1e12].  STRAY_ERANGE
 * when the rate is not reached in that span.
 */
int stray_fdr_alpha_required(const struct stray_fdr_model *m,
			     stray_real rate, stray_real *alpha_req,
			     struct stray_error *err);

#endif /* STRAY_FDR_H */
