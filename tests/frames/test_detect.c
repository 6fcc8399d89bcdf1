/*
 * test_detect.c - both star detectors (frames/include/frames/frames_detect.h) find stars
 * injected at known positions, and report no star on a star-free frame
 * whose noise is far below threshold.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "frames_fixture.h"

#define W 256
#define N_STARS 6

static const struct stray_star truth[N_STARS] = {
	{ 40.2, 50.7, 5.0, 3000.0 }, { 200.5, 40.1, 5.0, 2500.0 },
	{ 128.9, 128.3, 5.0, 5000.0 }, { 60.4, 210.6, 5.0, 2000.0 },
	{ 215.7, 190.2, 5.0, 4000.0 }, { 150.0, 80.5, 5.0, 1800.0 },
};

static void render(double stray_e, uint16_t *dn, float *e, int with_stars)
{
	struct stray_frame_cfg c;

	stray_frame_cfg_defaults(&c, W, W);
	c.stray_e = stray_e;
	c.dark_e = 0.4;
	c.read_noise_e = 3.0;
	stray_frame_expect(&c, truth, with_stars ? N_STARS : 0, e);
	stray_frame_sample(&c, e, 77, dn);
}

/* A quiet frame (~ 100 e-/px), with or without the stars, through both
 * detectors. */
static void detect_quiet(int with_stars, struct frames_detect_out out[2])
{
	static uint16_t dn[W * W];
	static float e[W * W];
	struct frames_model fm;
	struct frames_detect_cfg dc;
	char msg[128];

	fixture_model(&fm, 1e-6, W);
	frames_detect_cfg_init(&dc, &fm, stray_sensor_st16_like());
	render(fm.stray_e, dn, e, with_stars);
	assert_int_equal(frames_detect(dn, W, W, &dc, FRAMES_DET_THESIS |
				       FRAMES_DET_THRESHOLD, out, NULL, msg,
				       sizeof(msg)), 0);
}

static void test_detect_finds_injected_stars(void **state)
{
	struct frames_detection det[2][256];
	struct frames_detect_out out[2] = { { det[0], 256, 0 }, { det[1], 256, 0 } };
	int d, k;
	size_t i;

	(void)state;
	detect_quiet(1, out);
	for (d = 0; d < 2; d++) {
		assert_int_equal(out[d].n, N_STARS);
		for (k = 0; k < N_STARS; k++) {
			double best = 1e9;

			for (i = 0; i < out[d].n; i++)
				best = fmin(best, hypot(out[d].det[i].x - truth[k].x,
							out[d].det[i].y - truth[k].y));
			/* the threshold detector centroids the star; the
			 * window sum's region is centred on it */
			print_message("detector %d star %d: %.2f px\n", d, k, best);
			assert_true(best < (d ? 0.5 : 1.0));
		}
		assert_int_equal(frames_count_false(&out[d], truth, N_STARS, 0.0,
						    4.0, NULL, NULL, NULL, 0), 0);
	}
}

static void test_detect_quiet_frame_is_empty(void **state)
{
	struct frames_detection det[2][16];
	struct frames_detect_out out[2] = { { det[0], 16, 0 }, { det[1], 16, 0 } };

	(void)state;
	detect_quiet(0, out);
	assert_int_equal(out[0].n, 0);
	assert_int_equal(out[1].n, 0);
	/* and a detection far from every star is false */
	det[0][0].x = 10.0;
	det[0][0].y = 10.0;
	out[0].n = 1;
	assert_int_equal(frames_count_false(&out[0], truth, N_STARS, 0.0, 4.0,
					    NULL, NULL, NULL, 0), 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_detect_finds_injected_stars),
		cmocka_unit_test(test_detect_quiet_frame_is_empty),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
