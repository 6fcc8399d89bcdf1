/*
 * test_render.c - the frame renderer (libstray/frames, stray/frames.h):
 * flat-frame mean and variance against the closed form (eq. 2.3-2.6 plus
 * the camera), star photon totals (eq. 2.12), reproducibility, and the
 * synthetic star counts.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "stray/frames.h"

#define W 256

static void moments(const uint16_t *dn, size_t n, double *mean, double *var)
{
	double s = 0, s2 = 0;
	size_t i;

	for (i = 0; i < n; i++)
		s += dn[i];
	*mean = s / n;
	for (i = 0; i < n; i++)
		s2 += (dn[i] - *mean) * (dn[i] - *mean);
	*var = s2 / (n - 1);
}

/* A flat frame: DN mean (I + d)/g + bias, variance (I + d + r^2)/g^2 + 1/12. */
static void check_flat(double stray_e)
{
	struct stray_frame_cfg c;
	size_t n = (size_t)W * W;
	float *e = malloc(n * sizeof(float));
	uint16_t *dn = malloc(n * sizeof(uint16_t));
	double mean, var, g = STRAY_FRAMES_GAIN_E_PER_DN, mu, v;

	assert_non_null(e);
	assert_non_null(dn);
	stray_frame_cfg_defaults(&c, W, W);
	c.stray_e = stray_e;
	c.dark_e = 0.4;
	c.read_noise_e = 3.0;
	stray_frame_expect(&c, NULL, 0, e);
	stray_frame_sample(&c, e, 42, dn);
	moments(dn, n, &mean, &var);
	mu = (stray_e + 0.4) / g + STRAY_FRAMES_BIAS_DN;
	v = (stray_e + 0.4 + 9.0) / (g * g) + 1.0 / 12.0;
	/* 5 standard errors of the mean; the variance to 3 % (its s.e. is
	 * sqrt(2/n) = 0.55 %) */
	assert_true(fabs(mean - mu) < 5.0 * sqrt(v / n));
	assert_true(fabs(var / v - 1.0) < 0.03);
	free(e);
	free(dn);
}

static void test_render_flat_poisson_small(void **state)
{
	(void)state;
	check_flat(4.0);	/* inversion sampler (mean < 10) */
}

static void test_render_flat_ptrs(void **state)
{
	(void)state;
	check_flat(700.0);	/* transformed rejection (PTRS) */
}

/* eq. 2.12: a star's expected photons all land within its window. */
static void test_render_star_total(void **state)
{
	struct stray_frame_cfg c;
	struct stray_star s = { 100.3, 120.8, 5.0, 20000.0 };
	size_t n = (size_t)W * W, i;
	float *e = calloc(n, sizeof(float));
	uint16_t *dn = malloc(n * sizeof(uint16_t));
	double sum = 0, win = 0;
	int x, y;

	(void)state;
	assert_non_null(e);
	assert_non_null(dn);
	stray_frame_cfg_defaults(&c, W, W);
	stray_frame_expect(&c, &s, 1, e);
	for (i = 0; i < n; i++)
		sum += e[i];
	assert_true(fabs(sum / 20000.0 - 1.0) < 1e-4);
	stray_frame_sample(&c, e, 7, dn);
	for (y = 114; y <= 127; y++)	/* 6 px around the star's pixel */
		for (x = 94; x <= 106; x++)
			if ((x - 100) * (x - 100) + (y - 120) * (y - 120) <= 36)
				win += (dn[(size_t)y * W + x] -
					STRAY_FRAMES_BIAS_DN) *
				       STRAY_FRAMES_GAIN_E_PER_DN;
	/* > 99.9 % inside (sigma = 1.5 px), Poisson s.e. 141 e- */
	assert_true(fabs(win - 20000.0) < 5.0 * 141.0 + 30.0);
	free(e);
	free(dn);
}

static void test_render_reproducible(void **state)
{
	struct stray_frame_cfg c;
	size_t n = 64 * 64, i, diff = 0;
	float e[64 * 64];
	uint16_t a[64 * 64], b[64 * 64], d[64 * 64];

	(void)state;
	stray_frame_cfg_defaults(&c, 64, 64);
	c.stray_e = 300.0;
	c.read_noise_e = 3.0;
	stray_frame_expect(&c, NULL, 0, e);
	stray_frame_sample(&c, e, stray_frame_seed(5, 1), a);
	stray_frame_sample(&c, e, stray_frame_seed(5, 1), b);
	stray_frame_sample(&c, e, stray_frame_seed(5, 2), d);
	for (i = 0; i < n; i++) {
		assert_int_equal(a[i], b[i]);
		diff += a[i] != d[i];
	}
	assert_true(diff > n / 2);
}

/* Saturation: a pixel far above full scale reads SATLEVEL. */
static void test_render_saturates(void **state)
{
	struct stray_frame_cfg c;
	float e[16];
	uint16_t dn[16];
	int i;

	(void)state;
	stray_frame_cfg_defaults(&c, 4, 4);
	for (i = 0; i < 16; i++)
		e[i] = 1e6f;
	stray_frame_sample(&c, e, 1, dn);
	for (i = 0; i < 16; i++)
		assert_int_equal(dn[i], STRAY_FRAMES_SAT_DN);
}

/* The star field follows N(<m): counts and the magnitude slope. */
static void test_star_field_counts(void **state)
{
	static struct stray_star st[20000];
	struct stray_star_field f = { 200.0, 4.0, 9.0, 2.4e5 };
	double expect = (stray_star_counts_per_deg2(9.0) -
			 stray_star_counts_per_deg2(4.0)) * 200.0;
	size_t n, i, bright = 0;

	(void)state;
	assert_true(fabs(stray_star_counts_per_deg2(6.0) - 0.121) < 1e-12);
	stray_star_field_draw(&f, 2592, 1944, 3, st, 20000, &n);
	assert_true(fabs((double)n - expect) < 5.0 * sqrt(expect));
	for (i = 0; i < n; i++) {
		assert_true(st[i].mag >= 4.0 && st[i].mag <= 9.0);
		assert_true(st[i].x >= 0 && st[i].x < 2592);
		/* eq. 2.2: F(m) = F_0 10^(-0.4 m) */
		assert_true(fabs(st[i].photons_e /
				 (2.4e5 * pow(10.0, -0.4 * st[i].mag)) - 1) < 1e-9);
		bright += st[i].mag < 8.0;
	}
	/* N(<8)/N(<9) = 10^-0.44 of the stars fainter than 4 (nearly all) */
	assert_true(fabs((double)bright / n - pow(10.0, -0.44)) < 0.05);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_render_flat_poisson_small),
		cmocka_unit_test(test_render_flat_ptrs),
		cmocka_unit_test(test_render_star_total),
		cmocka_unit_test(test_render_reproducible),
		cmocka_unit_test(test_render_saturates),
		cmocka_unit_test(test_star_field_counts),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
