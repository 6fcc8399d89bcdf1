/*
 * test_hidden.c - hidden-effect tests: frames rendered with an effect the
 * analysis is not told about (a stray-light gradient, hot pixels); the
 * validation must report that model and frames disagree and name the
 * effect, and must report agreement when nothing is hidden.  The truth
 * settings stay in render(); the analysis sees the DN frames only.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "frames_fixture.h"

#define W 512
#define FRAMES 8
#define STRAY_LEVEL_ALPHA 1.6e-6	/* ~ 700 e-/px, k_px = 1 */

struct hidden { double gradient, hot_frac, hot_e; };

/* Truth: the library renderer with the hidden effect switched on. */
static void render(const struct frames_model *fm, const struct hidden *h,
		   int i, float *e, uint16_t *dn)
{
	struct stray_frame_cfg c;

	stray_frame_cfg_defaults(&c, W, W);
	c.stray_e = fm->stray_e;
	c.dark_e = fm->dark_e;
	c.read_noise_e = fm->read_noise_e;
	c.gradient = h->gradient;
	c.hot_frac = h->hot_frac;
	c.hot_e = h->hot_e;
	stray_frame_expect(&c, NULL, 0, e);
	stray_frame_sample(&c, e, stray_frame_seed(9, (uint64_t)i), dn);
}

/* Analysis: detect, count, diagnose against the nominal model. */
static int analyse(const struct hidden *h, char *text, size_t size)
{
	static float e[W * W], fx[4096], fy[4096];
	static uint16_t dn[W * W];
	static struct frames_detection det[2][4096];
	static double tile_sum[16];
	float tiles[16];
	struct frames_model fm;
	struct frames_rates r;
	struct frames_detect_cfg dc;
	struct frames_detect_out out[2] = { { det[0], 4096, 0 }, { det[1], 4096, 0 } };
	struct frames_evidence ev = { 4, 4, tile_sum, 0, fx, fy, 0, 4096 };
	struct stray_error err;
	long n_false = 0;
	char msg[128];
	int i, t;

	fixture_model(&fm, STRAY_LEVEL_ALPHA, W);
	assert_int_equal(frames_model_rates(&fm, &r, &err), STRAY_OK);
	frames_detect_cfg_init(&dc, &fm, stray_sensor_st16_like());
	memset(tile_sum, 0, sizeof(tile_sum));
	for (i = 0; i < FRAMES; i++) {
		render(&fm, h, i, e, dn);
		assert_int_equal(frames_detect(dn, W, W, &dc, FRAMES_DET_THESIS,
					       out, tiles, msg, sizeof(msg)), 0);
		for (t = 0; t < 16; t++)
			tile_sum[t] += tiles[t];
		n_false += (long)frames_count_false(&out[0], NULL, 0, 0.0, 6.0,
						    fx, fy, &ev.n_f, ev.max_f);
		ev.frames = i + 1;
	}
	i = frames_diagnose(&fm, &ev, (double)n_false / FRAMES, r.sliding, 128,
			    text, size);
	print_message("%s\n", text);
	return i;
}

static void test_hidden_nothing_agrees(void **state)
{
	struct hidden h = { 0.0, 0.0, 0.0 };
	char text[512];

	(void)state;
	assert_int_equal(analyse(&h, text, sizeof(text)), 0);
	assert_non_null(strstr(text, "agree"));
}

static void test_hidden_gradient_named(void **state)
{
	struct hidden h = { 0.6, 0.0, 0.0 };
	char text[512];

	(void)state;
	assert_int_equal(analyse(&h, text, sizeof(text)), 1);
	assert_non_null(strstr(text, "disagree"));
	assert_non_null(strstr(text, "gradient along columns"));
}

static void test_hidden_hot_pixels_named(void **state)
{
	struct hidden h = { 0.0, 2e-4, 3000.0 };
	char text[512];

	(void)state;
	assert_int_equal(analyse(&h, text, sizeof(text)), 1);
	assert_non_null(strstr(text, "hot pixels"));
	assert_null(strstr(text, "gradient"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hidden_nothing_agrees),
		cmocka_unit_test(test_hidden_gradient_named),
		cmocka_unit_test(test_hidden_hot_pixels_named),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
