/*
 * render.c - expected electrons and sampled DN of a detector frame
 * (frames.h): eq. 2.3 with k_px for the stray light, eq. 2.12 for the
 * stars, the camera model of rig/sim/vlab.c for the rest.
 */
#include <math.h>

#include "rng.h"
#include "stray/frames.h"

void stray_frame_cfg_defaults(struct stray_frame_cfg *c, int cols, int rows)
{
	static const struct stray_frame_cfg off;	/* no light, no noise,
							 * uniform, no truth
							 * effects */

	*c = off;
	c->cols = cols;
	c->rows = rows;
	c->gain_e_per_dn = STRAY_FRAMES_GAIN_E_PER_DN;
	c->bias_dn = STRAY_FRAMES_BIAS_DN;
	c->sat_dn = STRAY_FRAMES_SAT_DN;
	c->psf_sigma_px = 1.5;
}

uint64_t stray_frame_seed(uint64_t seed, uint64_t i)
{
	struct stray_frame_rng r;

	stray_frame_rng_init(&r, seed * 0x2545F4914F6CDD1Dull + i);
	stray_frame_rng_next(&r);
	return stray_frame_rng_next(&r);
}

/* Fraction of a unit Gaussian's mass in [a, b] (one axis of the PSF). */
static double gauss_mass(double a, double b, double sigma)
{
	double k = 1.0 / (sigma * sqrt(2.0));

	return 0.5 * (erf(b * k) - erf(a * k));
}

/* eq. 2.12: a star's photons, spread by the pixel-integrated PSF. */
static void add_star(const struct stray_frame_cfg *c,
		     const struct stray_star *s, float *e)
{
	enum { HALF = 8 };
	double fx[2 * HALF + 1], fy[2 * HALF + 1];
	int cx = (int)floor(s->x), cy = (int)floor(s->y), i, j;
	int h = (int)ceil(5.0 * c->psf_sigma_px);

	if (h > HALF)
		h = HALF;
	for (i = -h; i <= h; i++) {
		fx[i + h] = gauss_mass(cx + i - s->x, cx + i + 1 - s->x,
				       c->psf_sigma_px);
		fy[i + h] = gauss_mass(cy + i - s->y, cy + i + 1 - s->y,
				       c->psf_sigma_px);
	}
	for (j = -h; j <= h; j++) {
		int y = cy + j;

		if (y < 0 || y >= c->rows)
			continue;
		for (i = -h; i <= h; i++) {
			int x = cx + i;

			if (x >= 0 && x < c->cols)
				e[(size_t)y * c->cols + x] += (float)
					(s->photons_e * fx[i + h] * fy[j + h]);
		}
	}
}

/* Hot pixels sit at fixed detector places: a hash of (row, col). */
static int is_hot(const struct stray_frame_cfg *c, int row, int col)
{
	struct stray_frame_rng r;

	stray_frame_rng_init(&r, ((uint64_t)(row + c->row0) << 32) ^
			   (uint64_t)(col + c->col0) ^ 0x5EEDull);
	return stray_frame_rng_uniform(&r) < c->hot_frac;
}

void stray_frame_expect(const struct stray_frame_cfg *c,
			const struct stray_star *stars, size_t n_stars,
			float *expect_e)
{
	size_t i;
	int x, y;

	for (y = 0; y < c->rows; y++) {
		float *row = expect_e + (size_t)y * c->cols;

		for (x = 0; x < c->cols; x++) {
			/* eq. 2.3 with k_px: I_px = k_px alpha F t A_px */
			double s = c->stray_e;

			if (c->weight)
				s *= c->weight[(size_t)y * c->cols + x];
			if (c->gradient != 0.0)
				s *= 1.0 + c->gradient *
				     (2.0 * (x + 0.5) / c->cols - 1.0);
			row[x] = (float)(s + c->dark_e);
		}
	}
	for (i = 0; i < n_stars; i++)
		add_star(c, &stars[i], expect_e);
	if (c->hot_frac > 0.0)
		for (y = 0; y < c->rows; y++)
			for (x = 0; x < c->cols; x++)
				if (is_hot(c, y, x))
					expect_e[(size_t)y * c->cols + x] +=
						(float)c->hot_e;
}

void stray_frame_sample(const struct stray_frame_cfg *c,
			const float *expect_e, uint64_t seed, uint16_t *dn)
{
	struct stray_frame_rng r;
	double inv_gain = 1.0 / c->gain_e_per_dn, sat = c->sat_dn;
	size_t i, n = (size_t)c->rows * c->cols;

	stray_frame_rng_init(&r, seed);
	for (i = 0; i < n; i++) {
		/* eq. 2.4-2.6: shot noise, Poisson in the photo-electrons */
		double e = stray_frame_rng_poisson(&r, expect_e[i]) +
			   c->read_noise_e * stray_frame_rng_normal(&r);
		double v = floor(e * inv_gain + c->bias_dn + 0.5);

		dn[i] = (uint16_t)(v < 0.0 ? 0.0 : v > sat ? sat : v);
	}
}
