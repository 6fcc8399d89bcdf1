/*
 * frames_lost.c - stars found per magnitude by the detectors of `stray
 * frames` against the lost-star model (frames_lost.h).
 */
#include <math.h>
#include <string.h>

#include "frames/frames_lost.h"

int frames_lost_init(struct frames_lost *l, const struct frames_model *fm,
		     struct stray_error *err)
{
	static const enum stray_detector_kind kind[2] = {
		STRAY_DET_WINDOW, STRAY_DET_THRESHOLD
	};
	int d, i, rc;

	memset(l, 0, sizeof(*l));
	l->m = fm->m;		/* k_px folded into alpha_eff (frames_run.h) */
	l->alpha_eff = fm->alpha_eff;
	l->adc.stray_e = fm->stray_e;
	l->adc.dark_e = fm->dark_e;
	l->adc.read_noise_e = fm->read_noise_e;
	l->adc.gain_e_per_dn = STRAY_FRAMES_GAIN_E_PER_DN;
	for (d = 0; d < 2; d++) {
		stray_detector_init(&l->det[d], kind[d], l->m.n_pps);
		if ((rc = stray_detector_setup(&l->det[d], &l->m, err)))
			return rc;
		/* the very thresholds the OpenCV detectors use */
		l->det[d].i_sdt_e = fm->i_sdt_e;
		l->det[d].pixel_t_e = fm->pixel_threshold_e;
		for (i = 0; i < FRAMES_LOST_CACHE; i++)
			l->cache[d][i] = NAN;
	}
	return STRAY_OK;
}

/* The model for a star of photons e at magnitude mag, cached per 0.02. */
static double model_p(struct frames_lost *l, int d, double mag, double e)
{
	int k = (int)floor((mag - FRAMES_LOST_MAG0) / 0.02);
	double p = 0.0;

	if (k >= 0 && k < FRAMES_LOST_CACHE && !isnan(l->cache[d][k]))
		return l->cache[d][k];
	if (stray_detector_star_prob(&l->det[d], &l->m, l->alpha_eff, e, &p,
				     NULL) != STRAY_OK)
		p = NAN;
	if (k >= 0 && k < FRAMES_LOST_CACHE)
		l->cache[d][k] = p;
	return p;
}

void frames_lost_set_frame(struct frames_lost *l, const float *tiles,
			   int tiles_x, int tiles_y, int tile_px,
			   const float *weight, int cols, int rows)
{
	l->adc.tiles = tiles;
	l->adc.tiles_x = tiles_x;
	l->adc.tiles_y = tiles_y;
	l->adc.tile_px = tile_px;
	l->adc.weight = weight;
	l->adc.cols = cols;
	l->adc.rows = rows;
}

/* This frame's model for the star (the nominal one without tiles). */
static double frame_p(struct frames_lost *l, int d, const struct stray_star *s)
{
	double p = NAN;

	if (!l->adc.tiles)
		return model_p(l, d, s->mag, s->photons_e);
	if (frames_adc_star_prob(&l->adc, &l->det[d], &l->m, l->alpha_eff,
				 s->x, s->y, s->photons_e, &p, NULL) != STRAY_OK)
		p = NAN;
	return p;
}

void frames_lost_add(struct frames_lost *l,
		     const struct frames_detect_out out[2],
		     const double match[2], const struct stray_star *stars,
		     size_t n_stars)
{
	size_t i, j;
	int d;

	for (i = 0; i < n_stars; i++) {
		int b = (int)floor((stars[i].mag - FRAMES_LOST_MAG0) /
				   FRAMES_LOST_STEP);

		if (b < 0 || b >= FRAMES_LOST_BINS)
			continue;
		l->n[b]++;
		for (d = 0; d < 2; d++) {
			size_t n = out[d].n < out[d].max ? out[d].n : out[d].max;
			double m2 = match[d] * match[d];
			int hit = 0;

			if (d == 0)
				hit = frames_adc_window_found(&out[0], stars[i].x,
							      stars[i].y, match[0]);
			for (j = 0; d == 1 && j < n && !hit; j++) {
				double dx = out[d].det[j].x - stars[i].x;
				double dy = out[d].det[j].y - stars[i].y;

				hit = dx * dx + dy * dy <= m2;
			}
			l->found[d][b] += hit;
			l->model[d][b] += frame_p(l, d, &stars[i]);
			l->nominal[d][b] += model_p(l, d, stars[i].mag,
						    stars[i].photons_e);
		}
	}
}
