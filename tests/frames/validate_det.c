/*
 * validate_det.c - issue 28's detection-probability table for the OpenCV
 * detectors of `stray frames` (scripts/validate-det-frames.sh): 480 x 480
 * px frames from libstray's renderer, 100 stars of one brightness on a
 * 48 px grid at random sub-pixel places, uniform or mapped stray light
 * (a ramp 0.7-1.3 along columns times 1 + 0.005 sin sin of 256 px, the
 * map the model is told), frames_detect's window and threshold detectors;
 * found against this frame's model (frames_adc.h) and the sensor's.
 *
 *   validate_det FRAMES    (prints Markdown rows)
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frames/frames_adc.h"
#include "frames/frames_io.h"
#include "frames/frames_mapterm.h"
#include "frames/frames_run.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"
#include "star_grid.h"

#define W 480
#define GRID 48
#define NS ((W / GRID) * (W / GRID))
#define KPX 5.443

static struct frames_detection det[2][16384];
static float e[W * W], tiles[16], wmap[W * W];
static uint16_t dn[W * W];
static struct stray_detector d[2];

static void point(double alpha, double star_e, int mapped, int frames)
{
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_region_map map;
	struct frames_model fm;
	struct frames_detect_cfg dc;
	struct frames_detect_out out[2] = { { det[0], 16384, 0 },
					    { det[1], 16384, 0 } };
	struct stray_frame_cfg c;
	struct stray_star st[NS];
	struct frames_adc a;
	struct stray_fluxes f;
	uint64_t r = 1234567 + (uint64_t)(alpha * 1e10) + (uint64_t)star_e;
	long hit[2] = { 0, 0 }, nm = 0;
	double sum[2] = { 0, 0 }, nom[2], p, resid = 0;
	char msg[128];
	int fr, i, k;

	frames_map_regions(wmap, (size_t)W * W, &map);
	if (stray_reference_fluxes(s, &f, NULL) != STRAY_OK ||
	    frames_model_init(&fm, s, f.sun, f.drs, KPX, alpha, W, W,
			      mapped ? &map : NULL, NULL) != STRAY_OK)
		exit(1);
	frames_detect_cfg_init(&dc, &fm, s);
	if (mapped)
		resid = frames_map_resid_rel(wmap, W, W, 128);
	for (k = 0; k < 2; k++) {
		stray_detector_init(&d[k], k ? STRAY_DET_THRESHOLD :
				    STRAY_DET_WINDOW, fm.m.n_pps);
		if (stray_detector_setup(&d[k], &fm.m, NULL) != STRAY_OK)
			exit(1);
		d[k].i_sdt_e = fm.i_sdt_e;
		d[k].pixel_t_e = fm.pixel_threshold_e;
		d[k].bg_resid_rel = resid;
		if (stray_detector_star_prob(&d[k], &fm.m, fm.alpha_eff, star_e,
					     &nom[k], NULL) != STRAY_OK)
			exit(1);
	}
	stray_frame_cfg_defaults(&c, W, W);
	c.stray_e = fm.stray_e;
	c.weight = mapped ? wmap : NULL;
	c.dark_e = fm.dark_e;
	c.read_noise_e = fm.read_noise_e;
	c.psf_sigma_px = 1.5;
	star_grid_adc(&a, tiles, W, &fm, c.weight, STRAY_FRAMES_GAIN_E_PER_DN);
	for (fr = 0; fr < frames; fr++) {
		star_grid_place(st, W, GRID, star_e, &r);
		stray_frame_expect(&c, st, NS, e);
		stray_frame_sample(&c, e, stray_frame_seed(r, (uint64_t)fr), dn);
		if (frames_detect(dn, W, W, &dc, FRAMES_DET_THESIS |
				  FRAMES_DET_THRESHOLD, out, tiles, msg,
				  sizeof(msg)))
			exit(1);
		for (i = 0; i < NS; i++) {
			int h = 0, j;

			hit[0] += frames_adc_window_found(&out[0], st[i].x,
							  st[i].y, FRAMES_REACH_PX);
			for (j = 0; j < (int)out[1].n; j++)
				h |= hypot(out[1].det[j].x - st[i].x,
					   out[1].det[j].y - st[i].y) <= 4.0;
			hit[1] += h;
			if (i % 4 != fr % 4)
				continue;
			nm++;
			for (k = 0; k < 2; k++) {
				if (frames_adc_star_prob(&a, &d[k], &fm.m,
					fm.alpha_eff, st[i].x, st[i].y, star_e,
					&p, NULL) != STRAY_OK)
					exit(1);
				sum[k] += p;
			}
		}
	}
	for (k = 0; k < 2; k++) {
		double n = (double)frames * NS, m = hit[k] / n;
		double mod = sum[k] / nm, sig = sqrt(m * (1 - m) / n);
		int in = m >= 0.05 && m <= 0.95;

		printf("| %s | %s | %.3g | %.0f | %.0f | %.3f ± %.3f | %.3f | %+.3f | %s | %.3f | %+.3f |\n",
		       k ? "threshold" : "window", mapped ? "mapped" : "uniform",
		       alpha, star_e, n, m, sig, mod, mod - m,
		       !in ? "(outside 0.05-0.95)" :
		       fabs(mod - m) <= 0.05 ? "pass" : "FAIL", nom[k],
		       nom[k] - m);
	}
	fflush(stdout);
}

int main(int argc, char **argv)
{
	static const double pts[][2] = {
		{ 0, 1037 }, { 0, 1190 }, { 1e-7, 714 }, { 1e-7, 945 },
		{ 1.5e-7, 945 }, { 2e-7, 714 }, { 2e-7, 1037 }, { 2.5e-7, 945 },
		{ 2.5e-7, 1190 }, { 3e-7, 786 }, { 3e-7, 1037 }
	};
	int frames = argc > 1 ? atoi(argv[1]) : 12, mapped;
	unsigned i;

	star_grid_map(wmap, W, 0.005);
	printf("| detector | light | alpha | star e- | stars | found | model (this frame) | model - found | pass (0.05) | nominal model | nominal - found |\n");
	printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
	for (mapped = 0; mapped < 2; mapped++)
		for (i = 0; i < sizeof(pts) / sizeof(pts[0]); i++)
			point(pts[i][0], pts[i][1], mapped, frames);
	return 0;
}
