/*
 * test_accum.c - the temporal mean of repeated frames as light rates
 * (I - D(t)) / (t alpha_nd monitor) (thesis eq. 3.4-3.6), saturated
 * samples left out.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "stray/reduce_response.h"
#include "test_util.h"

static uint32_t hist[STRAY_DARK_HIST_LEN];

/* A dark model with level 100 in every channel at t = 0.1 s. */
static struct stray_dark_model *flat_dark(void)
{
	static uint16_t pix[8];
	static long rows[2] = { 0, 1 };
	struct stray_bayer_map map;
	struct stray_dark_model *m = malloc(sizeof(*m));
	struct stray_frame f = { 2, 4, pix, rows, 0, 0.1, 1.0, 1.0, 4095 };
	size_t i;

	for (i = 0; i < 8; i++)
		pix[i] = 100;
	stray_bayer_default(&map);
	stray_dark_init(m, &map);
	assert_int_equal(stray_dark_add(m, &f, hist, NULL), STRAY_OK);
	stray_dark_finish(m);
	return m;
}

static void test_accum_rate_mean_and_scatter(void **state)
{
	struct stray_dark_model *d = flat_dark();
	static const uint16_t vals[3] = { 150, 160, 170 };
	uint16_t pix[8];
	long rows[2] = { 0, 1 };
	struct stray_frame f = { 2, 4, pix, rows, 0, 0.1, 0.5, 2.0, 4095 };
	struct stray_accum a;
	void *mem = malloc(stray_accum_bytes(8));
	double k = 1.0 / (0.1 * 0.5 * 2.0);
	int i, p;

	(void)state;
	stray_accum_init(&a, 8, mem);
	for (i = 0; i < 3; i++) {
		for (p = 0; p < 8; p++)
			pix[p] = vals[i];
		pix[3] = i == 1 ? 4095 : vals[i];	/* saturated once */
		assert_int_equal(stray_accum_add(&a, d, &f, NULL), STRAY_OK);
	}
	/* eq. 3.4-3.5: (I - D) / (t nd m), mean over the frames */
	assert_near(a.mean[0], 60.0 * k, 1e-3);
	assert_int_equal(a.n[0], 3);
	/* Welford: sum of squares about the mean, (10 k)^2 * 2 */
	assert_near(a.m2[0], 200.0 * k * k, 1e-2);
	/* The saturated sample is left out, not averaged in (§3.2). */
	assert_int_equal(a.n[3], 2);
	assert_near(a.mean[3], 60.0 * k, 1e-3);
	assert_int_equal(a.n_sat, 1);
	/* dP/dD per channel: -1/(t nd m) per pixel and frame */
	assert_near(a.dcoef[0][0], -3.0 * k, 1e-9);
	stray_accum_reset(&a);
	assert_int_equal(a.n_frames, 0);
	assert_int_equal(a.n[0], 0);
	f.t_exp_s = 0.2;	/* no dark at 0.2 s */
	assert_int_equal(stray_accum_add(&a, d, &f, NULL), STRAY_ENOTFOUND);
	free(mem);
	free(d);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_accum_rate_mean_and_scatter),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
