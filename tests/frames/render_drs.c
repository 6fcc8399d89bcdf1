/*
 * render_drs.c - frames for the cedar-solve comparison (issue 28,
 * scripts/validate-cedar.sh): 256 x 256 px st16-like frames of uniform
 * stray light at alpha (consistent k_px), each with one designed
 * reference star (m 5.75) at a random place at least 16 px from the
 * edges, rendered by libstray/frames.  Writes per frame the star's x, y
 * (float32) and the DN pixels (uint16), little-endian, to OUT.  With
 * "mapped", the stray light follows a ramp 0.7-1.3 along columns times
 * 1 + 0.005 sin sin of 256 px (mean 1, as validate_det.c), and its 64
 * levels go to OUT.regions.csv (fraction,rel_alpha) for `stray fdr --map`.
 *
 *   render_drs ALPHA FRAMES SEED OUT [mapped]
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <math.h>
#include <string.h>

#include "frames/frames_io.h"
#include "star_grid.h"
#include "stray/fdr.h"
#include "stray/frames.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

#define W 256

int main(int argc, char **argv)
{
	static float expect[W * W];
	static uint16_t dn[W * W];
	static float wmap[W * W];
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_fdr_model m;
	struct stray_frame_cfg c;
	struct stray_fluxes f;
	struct stray_star star;
	uint64_t r;
	FILE *out;
	long i, n;

	if (argc != 5 && !(argc == 6 && strcmp(argv[5], "mapped") == 0))
		return fprintf(stderr, "usage: render_drs ALPHA FRAMES SEED OUT [mapped]\n"), 2;
	if (stray_reference_fluxes(s, &f, NULL) != STRAY_OK)
		return 1;
	stray_sensor_fdr_model(s, f.sun, f.drs, &m);
	stray_frame_cfg_defaults(&c, W, W);
	c.stray_e = stray_fdr_pixel_photons(&m, atof(argv[1]));
	c.dark_e = s->dark_current_e_s * s->t_exp_s;
	c.read_noise_e = s->read_noise_e;
	c.psf_sigma_px = 1.5;
	if (argc == 6) {
		struct stray_region_map map;
		char path[4096];
		unsigned k;

		star_grid_map(wmap, W, 0.005);
		c.weight = wmap;
		frames_map_regions(wmap, (size_t)W * W, &map);
		snprintf(path, sizeof(path), "%s.regions.csv", argv[4]);
		out = fopen(path, "w");
		if (!out)
			return 1;
		fprintf(out, "fraction,rel_alpha\n");
		for (k = 0; k < map.n; k++)
			fprintf(out, "%.9g,%.9g\n", map.fraction[k], map.rel_alpha[k]);
		if (fclose(out))
			return 1;
	}
	n = atol(argv[2]);
	r = (uint64_t)atol(argv[3]) * 0x9E3779B97F4A7C15ull + 7;
	out = fopen(argv[4], "wb");
	if (!out)
		return 1;
	star.mag = s->drs_mag;
	star.photons_e = stray_fdr_drs_photons(&m);
	for (i = 0; i < n; i++) {
		float xy[2];

		r = r * 6364136223846793005ull + 1442695040888963407ull;
		star.x = 16 + (W - 32) * (double)(r >> 11) / 9007199254740992.0;
		r = r * 6364136223846793005ull + 1442695040888963407ull;
		star.y = 16 + (W - 32) * (double)(r >> 11) / 9007199254740992.0;
		stray_frame_expect(&c, &star, 1, expect);
		stray_frame_sample(&c, expect, stray_frame_seed(r, (uint64_t)i), dn);
		xy[0] = (float)star.x;
		xy[1] = (float)star.y;
		if (fwrite(xy, sizeof(xy), 1, out) != 1 ||
		    fwrite(dn, sizeof(dn), 1, out) != 1)
			return 1;
	}
	return fclose(out) ? 1 : 0;
}
