/*
 * test_detector_mc.c - the lost-star and false-star models of the named
 * detectors (stray/detector.h) against frames rendered by libstray/frames
 * (Poisson shot noise, read noise, gain, bias, 12-bit ADC) and each
 * detector's rule applied here pixel by pixel (no OpenCV, no model code):
 *   window     the disk window's sum at every pixel above I_sdt, a star
 *              found when a window within 3 px of it clears;
 *   threshold  pixels above the fixed threshold, 8-connected regions of
 *              >= 5 px touching the star's pixel neighbourhood;
 *   tetra3     threshold k times the frame's RMS about the background,
 *              binary opening with the 3x3 cross, regions of >= 5 px.
 * The background is known (subtracted), as in issue 28's measurements;
 * tetra3 removes its own 25 px local mean, as get_centroids_from_image.
 * Issue 28's bar: detection probability within 0.05 where it lies in
 * 0.05-0.95, false stars per image within a factor 1.5 over 0.1-100.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "frames/frames_adc.h"
#include "stray/detector.h"
#include "stray/frames.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

#define W 240			/* rendered frame, px */
/* Star spacing: windows and tetra3's 25 px local means never share (at
 * 24 px tetra3's detection came out 0.06 below cedar-solve's own at 1e-7,
 * at 48 px it agrees with it and the model). */
#define GRID 48
#define NS ((W / GRID) * (W / GRID))

struct mc {
	struct stray_fdr_model m;
	struct stray_frame_cfg cfg;
	float expect[W * W], img[W * W];
	uint16_t dn[W * W];
	unsigned char mask[W * W], open[W * W], seen[W * W];
	struct stray_star stars[NS];
};

static struct mc *mc_new(void)
{
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct stray_fluxes f;
	struct mc *c = calloc(1, sizeof(*c));

	assert_non_null(c);
	assert_int_equal(stray_reference_fluxes(s, &f, NULL), STRAY_OK);
	stray_sensor_fdr_model(s, f.sun, f.drs, &c->m);
	/* the camera's noise: read noise with the ADC's 2 e- steps */
	c->m.read_noise_e = sqrt(s->read_noise_e * s->read_noise_e +
				 STRAY_FRAMES_GAIN_E_PER_DN *
				 STRAY_FRAMES_GAIN_E_PER_DN / 12.0);
	c->m.dark_current_e_s = s->dark_current_e_s;
	c->m.n_tot = (double)W * W;
	stray_frame_cfg_defaults(&c->cfg, W, W);
	c->cfg.dark_e = s->dark_current_e_s * s->t_exp_s;
	c->cfg.read_noise_e = s->read_noise_e;
	return c;
}

/* One frame at alpha, with the stars (nstar of star_e) or none, into
 * img as e- above the known background. */
static void render(struct mc *c, double alpha, double star_e, int nstar,
		   uint64_t seed)
{
	uint64_t r = seed * 0x9E3779B97F4A7C15ull + 1;
	double bg;
	int i;

	c->cfg.stray_e = stray_fdr_pixel_photons(&c->m, alpha);
	c->cfg.psf_sigma_px = 1.5;
	for (i = 0; i < nstar; i++) {
		int gx = i % (W / GRID), gy = i / (W / GRID);

		r = r * 6364136223846793005ull + 1442695040888963407ull;
		c->stars[i].x = gx * GRID + GRID / 2 + (double)(r >> 40) / (1 << 24);
		r = r * 6364136223846793005ull + 1442695040888963407ull;
		c->stars[i].y = gy * GRID + GRID / 2 + (double)(r >> 40) / (1 << 24);
		c->stars[i].mag = 5.75;
		c->stars[i].photons_e = star_e;
	}
	stray_frame_expect(&c->cfg, c->stars, (size_t)nstar, c->expect);
	stray_frame_sample(&c->cfg, c->expect, stray_frame_seed(seed, 0), c->dn);
	bg = c->cfg.stray_e + c->cfg.dark_e;
	for (i = 0; i < W * W; i++)
		c->img[i] = (float)((c->dn[i] - c->cfg.bias_dn) *
				    c->cfg.gain_e_per_dn - bg);
}

/* 8-connected region through (x, y) in mask, its size (bounded box). */
static int region(struct mc *c, const unsigned char *mask, int x0, int y0,
		  int stamp)
{
	static int qx[W * W], qy[W * W];
	int h = 0, t = 0, n = 0;

	if (!mask[y0 * W + x0] || c->seen[y0 * W + x0] == stamp)
		return 0;
	qx[t] = x0; qy[t++] = y0;
	c->seen[y0 * W + x0] = (unsigned char)stamp;
	while (h < t) {
		int x = qx[h], y = qy[h++], dx, dy;

		n++;
		for (dy = -1; dy <= 1; dy++)
			for (dx = -1; dx <= 1; dx++) {
				int u = x + dx, v = y + dy;

				if (u < 0 || v < 0 || u >= W || v >= W ||
				    !mask[v * W + u] || c->seen[v * W + u] == stamp)
					continue;
				c->seen[v * W + u] = (unsigned char)stamp;
				qx[t] = u; qy[t++] = v;
			}
	}
	return n;
}

/* Regions of >= min_px in mask: every one (false stars, no stars drawn),
 * or those touching each star's 3x3 pixels (found stars). */
static int count_regions(struct mc *c, const unsigned char *mask, int nstar,
			 unsigned min_px)
{
	int i, x, y, found = 0;

	memset(c->seen, 0, sizeof(c->seen));
	if (nstar == 0) {
		for (y = 0; y < W; y++)
			for (x = 0; x < W; x++)
				found += region(c, mask, x, y, 1) >= (int)min_px;
		return found;
	}
	for (i = 0; i < nstar; i++) {
		int sx = (int)c->stars[i].x, sy = (int)c->stars[i].y, hit = 0;

		for (y = sy - 1; y <= sy + 1 && !hit; y++)
			for (x = sx - 1; x <= sx + 1 && !hit; x++)
				hit = region(c, mask, x, y, 1) >= (int)min_px;
		found += hit;
	}
	return found;
}

static int detect_threshold(struct mc *c, double t, unsigned min_px, int nstar)
{
	int i;

	for (i = 0; i < W * W; i++)
		c->mask[i] = c->img[i] > t;
	return count_regions(c, c->mask, nstar, min_px);
}

/* tetra3's local mean: the 25 x 25 box mean of the frame (clipped at
 * the edges) removed from every pixel, the star's own light included. */
static void local_mean(struct mc *c)
{
	static double sat[(W + 1) * (W + 1)];
	int x, y;

	for (y = 0; y <= W; y++)
		for (x = 0; x <= W; x++)
			sat[y * (W + 1) + x] = x == 0 || y == 0 ? 0 :
				c->img[(y - 1) * W + x - 1] +
				sat[(y - 1) * (W + 1) + x] +
				sat[y * (W + 1) + x - 1] -
				sat[(y - 1) * (W + 1) + x - 1];
	for (y = 0; y < W; y++)
		for (x = 0; x < W; x++) {
			int x0 = x - 12 < 0 ? 0 : x - 12, y0 = y - 12 < 0 ? 0 : y - 12;
			int x1 = x + 13 > W ? W : x + 13, y1 = y + 13 > W ? W : y + 13;
			double s = sat[y1 * (W + 1) + x1] - sat[y0 * (W + 1) + x1] -
				   sat[y1 * (W + 1) + x0] + sat[y0 * (W + 1) + x0];

			c->mask[y * W + x] = 0;
			c->open[y * W + x] = 0;
			c->seen[y * W + x] = 0;
			c->expect[y * W + x] = (float)(s / ((x1 - x0) * (y1 - y0)));
		}
	for (x = 0; x < W * W; x++)
		c->img[x] -= c->expect[x];
}

static int detect_tetra3(struct mc *c, double k, unsigned min_px, int nstar)
{
	double ss = 0;
	long n = 0;
	int i, x, y;

	local_mean(c);
	/* The frame's RMS about the background as a sparse sky gives it:
	 * the grid's stars packed here would lift it by 30 %, one DRS in a
	 * 256 px frame by 1 %, so pixels near a star are left out. */
	for (y = 0; y < W; y++)
		for (x = 0; x < W; x++) {
			int ox = x % GRID - GRID / 2, oy = y % GRID - GRID / 2;

			if (ox * ox + oy * oy < 64)
				continue;
			ss += (double)c->img[y * W + x] * c->img[y * W + x];
			n++;
		}
	for (i = 0; i < W * W; i++)
		c->mask[i] = c->img[i] > k * sqrt(ss / n);
	/* binary opening, 3x3 cross: erode, then dilate */
	memset(c->open, 0, sizeof(c->open));
	for (y = 1; y < W - 1; y++)
		for (x = 1; x < W - 1; x++)
			if (c->mask[y * W + x] && c->mask[y * W + x - 1] &&
			    c->mask[y * W + x + 1] && c->mask[(y - 1) * W + x] &&
			    c->mask[(y + 1) * W + x]) {
				c->open[y * W + x] |= 1;
				c->open[y * W + x - 1] |= 2;
				c->open[y * W + x + 1] |= 2;
				c->open[(y - 1) * W + x] |= 2;
				c->open[(y + 1) * W + x] |= 2;
			}
	return count_regions(c, c->open, nstar, min_px);
}

/* A window of radius r within 3 px of a star clears t. */
static int detect_window(struct mc *c, double r, double t, int nstar)
{
	int i, ir = (int)r, found = 0;

	for (i = 0; i < nstar; i++) {
		int sx = (int)c->stars[i].x, sy = (int)c->stars[i].y, x, y, u, v;
		int hit = 0;

		for (y = sy - 3; y <= sy + 3 && !hit; y++)
			for (x = sx - 3; x <= sx + 3 && !hit; x++) {
				double sum = 0, ex = x + 0.5 - c->stars[i].x;
				double ey = y + 0.5 - c->stars[i].y;

				if (ex * ex + ey * ey > 9.0)
					continue;
				for (v = -ir; v <= ir; v++)
					for (u = -ir; u <= ir; u++)
						if (u * u + v * v <= r * r)
							sum += c->img[(y + v) * W + x + u];
				hit = sum > t;
			}
		found += hit;
	}
	return found;
}

/* Measured and modelled detection of the DRS at alpha, one detector. */
static void check_prob(struct mc *c, struct stray_detector *d, double alpha,
		       double star, int frames, double *meas, double *model)
{
	long found = 0;
	int f;

	assert_int_equal(stray_detector_setup(d, &c->m, NULL), STRAY_OK);
	for (f = 0; f < frames; f++) {
		render(c, alpha, star, NS, (uint64_t)(1000 * d->kind + f + 1));
		if (d->kind == STRAY_DET_WINDOW)
			found += detect_window(c, d->window_r_px, d->i_sdt_e, NS);
		else if (d->kind == STRAY_DET_THRESHOLD)
			found += detect_threshold(c, d->pixel_t_e, d->min_px, NS);
		else
			found += detect_tetra3(c, d->sigma_k, d->min_px, NS);
	}
	*meas = (double)found / ((double)frames * NS);
	if (d->kind == STRAY_DET_THRESHOLD) {
		/* The test's pixels are whole DN: the threshold's place on
		 * the ADC's 2 e- steps, exactly (frames_adc.h eq. 1), with the
		 * background known; the steps leave the variance. */
		static struct stray_detector dd;
		struct stray_fdr_model mm = c->m;
		double level = c->cfg.stray_e + c->cfg.dark_e;

		dd = *d;
		dd.pixel_t_e = frames_adc_threshold(d->pixel_t_e, level, level,
						    c->cfg.gain_e_per_dn);
		mm.read_noise_e = c->cfg.read_noise_e;
		assert_int_equal(stray_detector_star_prob(&dd, &mm, alpha, star,
							  model, NULL), STRAY_OK);
	} else
		assert_int_equal(stray_detector_star_prob(d, &c->m, alpha, star,
							  model, NULL), STRAY_OK);
	printf("# %-9s k %g alpha %.3g star %.0f e-: P model %.3f measured %.3f (%d stars)\n",
	       stray_detector_name(d->kind), d->sigma_k, alpha, star, *model,
	       *meas, frames * NS);
}

static void prob_case(enum stray_detector_kind kind, double sigma_k,
		      double star_frac, const double *alpha, int n, int frames)
{
	struct mc *c = mc_new();
	struct stray_detector d;
	int i, in_range = 0;

	for (i = 0; i < n; i++) {
		double meas, model;

		stray_detector_init(&d, kind, c->m.n_pps);
		d.sigma_k = sigma_k;
		check_prob(c, &d, alpha[i],
			   star_frac * stray_fdr_drs_photons(&c->m), frames,
			   &meas, &model);
		if (meas >= 0.05 && meas <= 0.95) {
			in_range++;
			assert_true(fabs(model - meas) <= 0.05);
		}
	}
	assert_true(in_range >= 2);	/* the range was covered */
	free(c);
}

static void test_window_lost(void **state)
{
	static const double a[] = { 0, 1e-7, 2e-7, 3e-7, 4e-7, 6e-7, 1e-6 };

	(void)state;
	prob_case(STRAY_DET_WINDOW, 3, 1, a, 7, 32);
}

static void test_threshold_lost(void **state)
{
	static const double a[] = { 0, 5e-8, 1e-7, 1.5e-7, 2e-7 };

	(void)state;
	prob_case(STRAY_DET_THRESHOLD, 3, 0.6, a, 5, 32);
}

/* The DRS itself through the threshold detector: ~0.95 from 0 to 4e-7,
 * right at Pr_drs, so whether lost stars bind turns on 0.01: the
 * component model (detector_blob.c) must hold to that.  The rule it
 * replaced said 0.965-0.98 here, and "never" for the lost-star limit. */
static void test_threshold_drs(void **state)
{
	static const double a[] = { 1e-7, 3e-7 };
	struct mc *c = mc_new();
	struct stray_detector d;
	double meas, model;
	int i;

	(void)state;
	for (i = 0; i < 2; i++) {
		stray_detector_init(&d, STRAY_DET_THRESHOLD, c->m.n_pps);
		check_prob(c, &d, a[i], stray_fdr_drs_photons(&c->m), 64, &meas,
			   &model);
		assert_true(fabs(model - meas) <= 0.015);
	}
	free(c);
}

static void test_tetra3_lost(void **state)
{
	static const double a[] = { 5e-8, 7e-8, 1e-7, 1.5e-7 };
	static const double a5[] = { 2e-8, 3e-8, 5e-8, 7e-8 };

	(void)state;
	prob_case(STRAY_DET_TETRA3, 3, 1, a, 4, 32);
	prob_case(STRAY_DET_TETRA3, 5, 1, a5, 4, 32);
}

/* False stars per frame without stars: measured over frames, modelled by
 * stray_detector_log_false_rate for the frame's pixels. */
static void false_case(enum stray_detector_kind kind, double sigma_k,
		       double alpha, int frames, double *meas, double *model)
{
	struct mc *c = mc_new();
	struct stray_detector d;
	long n = 0;
	double lr;
	int f;

	stray_detector_init(&d, kind, c->m.n_pps);
	d.sigma_k = sigma_k;
	assert_int_equal(stray_detector_setup(&d, &c->m, NULL), STRAY_OK);
	for (f = 0; f < frames; f++) {
		render(c, alpha, 0, 0, (uint64_t)(5000 + f));
		n += kind == STRAY_DET_TETRA3 ?
			detect_tetra3(c, sigma_k, d.min_px, 0) :
			detect_threshold(c, d.pixel_t_e, d.min_px, 0);
	}
	assert_int_equal(stray_detector_log_false_rate(&d, &c->m, alpha, &lr,
						       NULL), STRAY_OK);
	*meas = (double)n / frames;
	*model = exp(lr);
	printf("# %-9s k %g alpha %.3g: false stars per %d px frame model %.3g "
	       "measured %.3g (%ld)\n", stray_detector_name(kind), sigma_k,
	       alpha, W, *model, *meas, n);
	free(c);
}

static void test_tetra3_false(void **state)
{
	/* k sigma is constant-false-alarm: false stars appear only at
	 * small k (k = 3, the default, gives ~1e-8 per full image) */
	static const double k[] = { 1.1, 1.2, 1.3, 1.5 };
	double meas, model;
	int i;

	(void)state;
	for (i = 0; i < 4; i++) {
		false_case(STRAY_DET_TETRA3, k[i], 1e-7, 150, &meas, &model);
		if (meas >= 0.1)
			assert_true(model / meas <= 1.5 && meas / model <= 1.5);
	}
	/* the rate does not follow the light */
	false_case(STRAY_DET_TETRA3, 1.2, 4e-7, 150, &meas, &model);
	assert_true(model / meas <= 1.5 && meas / model <= 1.5);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_window_lost),
		cmocka_unit_test(test_threshold_lost),
		cmocka_unit_test(test_threshold_drs),
		cmocka_unit_test(test_tetra3_lost),
		cmocka_unit_test(test_tetra3_false),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
