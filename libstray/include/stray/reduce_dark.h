/*
 * reduce_dark.h - the dark model D(t_exp) per Bayer read channel (thesis
 * §3.2, eq. 3.3) and the hot/dead pixel mask found from the dark frames.
 *
 * Two passes over the darks, each streaming one frame at a time:
 *   1. stray_dark_add: a sigma-clipped mean of each channel of each frame
 *      (so hot pixels do not bias the level), averaged per exposure time;
 *   2. stray_pixstat_add: the per-pixel excess over that level, whose mean
 *      and scatter classify hot (dark current far above the rest) and dead
 *      (stuck: no temporal noise, or far below the level) pixels.
 * No heap: the model is a fixed-size struct, per-pixel buffers are the
 * caller's.
 */
#ifndef STRAY_REDUCE_DARK_H
#define STRAY_REDUCE_DARK_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"
#include "stray/reduce_frame.h"

#define STRAY_DARK_LEVELS_MAX 32
/* Two exposure times within this relative tolerance are the same one. */
#define STRAY_DARK_T_REL_TOL 1e-6
/* Clip at this many robust sigmas (1.4826 MAD) about the channel median. */
#define STRAY_DARK_CLIP_SIGMA 5.0

struct stray_dark_level {
	double t_exp_s;
	unsigned long n_frames;
	double sum[STRAY_BAYER_CHANNELS];	/* of per-frame clipped means */
	double var_sum[STRAY_BAYER_CHANNELS];	/* of per-frame pixel vars */
	double n_pix[STRAY_BAYER_CHANNELS];	/* clipped pixels, all frames */
	/* After stray_dark_finish: */
	double mean[STRAY_BAYER_CHANNELS];	/* D_c(t), counts */
	double var[STRAY_BAYER_CHANNELS];	/* per-pixel variance, counts^2 */
	double var_mean[STRAY_BAYER_CHANNELS];	/* variance of mean[] */
};

struct stray_dark_model {
	struct stray_bayer_map map;
	size_t n;
	struct stray_dark_level lvl[STRAY_DARK_LEVELS_MAX];
};

void stray_dark_init(struct stray_dark_model *m,
		     const struct stray_bayer_map *map);

/* Counts histogram per channel: the clipped mean costs O(pixels). */
#define STRAY_DARK_HIST_LEN (STRAY_BAYER_CHANNELS * 65536u)

/*
 * Pass 1: add a dark frame.  hist is caller scratch of STRAY_DARK_HIST_LEN
 * counters.  STRAY_ERANGE when more than STRAY_DARK_LEVELS_MAX exposure
 * times appear.
 */
int stray_dark_add(struct stray_dark_model *m, const struct stray_frame *f,
		   uint32_t *hist, struct stray_error *err);

void stray_dark_finish(struct stray_dark_model *m);

/* Index of the level matching t_exp_s, or STRAY_ENOTFOUND ("EXPTIME"). */
int stray_dark_find(const struct stray_dark_model *m, double t_exp_s,
		    size_t *index, struct stray_error *err);

/* Per-pixel statistics of the dark excess I - D_c(t), Welford's update. */
struct stray_pixstat {
	size_t n_pix;
	double *mean;		/* n_pix, caller-owned */
	double *m2;		/* n_pix, caller-owned */
	unsigned long n;	/* frames added */
};

void stray_pixstat_init(struct stray_pixstat *s, size_t n_pix, double *mean,
			double *m2);

/* Pass 2: add a dark frame (its level must be in m). */
int stray_pixstat_add(struct stray_pixstat *s,
		      const struct stray_dark_model *m,
		      const struct stray_frame *f, struct stray_error *err);

enum stray_pixel_flag {
	STRAY_PIX_OK = 0,
	STRAY_PIX_HOT = 1,	/* dark excess above the rest by hot_sigma */
	STRAY_PIX_DEAD = 2,	/* stuck: no temporal noise, or far low */
	STRAY_PIX_SAT = 4	/* saturated in every frame of a group */
};

struct stray_mask_stats {
	size_t n_hot, n_dead;
	double excess_median, excess_sigma;	/* robust, counts */
};

/*
 * Classify pixels against the robust spread of the mean dark excess
 * (median, 1.4826 MAD): hot above median + hot_sigma spreads, dead below
 * median - hot_sigma spreads or stuck (no change at all over 4 or more
 * darks).  mask gets n_pix enum stray_pixel_flag values (other flags
 * cleared); scratch n_pix doubles.  STRAY_EINVAL with fewer than 2 darks.
 */
int stray_mask_build(const struct stray_pixstat *s, double hot_sigma,
		     uint8_t *mask, double *scratch,
		     struct stray_mask_stats *out, struct stray_error *err);

#endif /* STRAY_REDUCE_DARK_H */
