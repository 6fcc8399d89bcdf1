/*
 * star_grid.h - the synthetic scenes the detector validations render
 * (test_detect_gap, test_map_term, validate_det, render_drs): a focal map
 * with a ramp and a ripple its 128 px tiles cannot follow, a jittered grid
 * of equal stars, and the ADC view of a frame's model.  Truth only: what a
 * detector is told comes from the model, never from here.
 */
#ifndef STRAY_TESTS_STAR_GRID_H
#define STRAY_TESTS_STAR_GRID_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "frames/frames_adc.h"
#include "frames/frames_run.h"
#include "stray/frames.h"

/* A ramp 0.7-1.3 along columns times 1 + amp sin sin of a 256 px period,
 * scaled to mean 1, on a w x w frame (the literal pi keeps the maps
 * of the recorded validation runs bit for bit). */
static inline void star_grid_map(float *wmap, int w, double amp)
{
	double sum = 0;
	int x, y;

	for (y = 0; y < w; y++)
		for (x = 0; x < w; x++) {
			double v = (0.7 + 0.6 * (x + 0.5) / w) *
				   (1 + amp * sin(2 * 3.14159265358979 * (x + 0.5) / 256) *
				    sin(2 * 3.14159265358979 * (y + 0.5) / 256));

			wmap[y * w + x] = (float)v;
			sum += v;
		}
	for (x = 0; x < w * w; x++)
		wmap[x] = (float)(wmap[x] / (sum / ((double)w * w)));
}

/* (w / grid)^2 stars of star_e, one a grid cell, each placed uniformly
 * within a pixel of its cell's centre by the LCG state *r. */
static inline void star_grid_place(struct stray_star *st, int w, int grid,
				   double star_e, uint64_t *r)
{
	int i, n = (w / grid) * (w / grid);

	for (i = 0; i < n; i++) {
		*r = *r * 6364136223846793005ull + 1442695040888963407ull;
		st[i].x = (i % (w / grid)) * grid + grid / 2 +
			  (double)(*r >> 40) / (1 << 24);
		*r = *r * 6364136223846793005ull + 1442695040888963407ull;
		st[i].y = (i / (w / grid)) * grid + grid / 2 +
			  (double)(*r >> 40) / (1 << 24);
		st[i].mag = 6;
		st[i].photons_e = star_e;
	}
}

/* The ADC view of a w x w frame of model fm: 4 x 4 tiles of 128 px. */
static inline void star_grid_adc(struct frames_adc *a, float *tiles, int w,
				 const struct frames_model *fm,
				 const float *weight, double gain_e_per_dn)
{
	memset(a, 0, sizeof(*a));
	a->tiles = tiles;
	a->tiles_x = a->tiles_y = 4;
	a->tile_px = 128;
	a->cols = a->rows = w;
	a->weight = weight;
	a->stray_e = fm->stray_e;
	a->dark_e = fm->dark_e;
	a->read_noise_e = fm->read_noise_e;
	a->gain_e_per_dn = gain_e_per_dn;
}

#endif /* STRAY_TESTS_STAR_GRID_H */
