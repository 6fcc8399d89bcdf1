/*
 * test_dark.c - the dark model per Bayer read channel (thesis §3.2,
 * eq. 3.3): sigma-clipped channel means matched on exposure time.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdlib.h>

#include "stray/reduce_dark.h"
#include "test_util.h"

#define ROWS 8
#define COLS 16

static uint32_t hist[STRAY_DARK_HIST_LEN];
static const double offset[8] = { 100, 104, 97, 110, 95, 102, 108, 99 };

/* Channel offset with a -3..+3 pattern, plus two hot pixels. */
static void dark_frame(uint16_t *pix, long *rows, int hot, double t,
		       struct stray_frame *f)
{
	struct stray_bayer_map m;
	size_t r, c;

	stray_bayer_default(&m);
	for (r = 0; r < ROWS; r++) {
		rows[r] = (long)r;
		for (c = 0; c < COLS; c++)
			pix[r * COLS + c] = (uint16_t)(offset[stray_bayer_channel(
				&m, (long)r, (long)c)] + 2.0 * ((r / 2 + c / 4 + r % 2) % 4) - 3.0);
	}
	if (hot) {
		pix[0] += 500;	/* channel 0 */
		pix[COLS + 1] += 800;	/* channel 5 */
	}
	*f = (struct stray_frame){ ROWS, COLS, pix, rows, 0, t, 1.0, 1.0, 4095 };
}

static void test_dark_levels_per_channel_ignore_hot(void **state)
{
	uint16_t pix[ROWS * COLS];
	long rows[ROWS];
	struct stray_bayer_map map;
	struct stray_dark_model *m = malloc(sizeof(*m));
	struct stray_frame f;
	struct stray_error err;
	size_t li;
	unsigned ch;
	double naive = 0.0;

	(void)state;
	stray_bayer_default(&map);
	stray_dark_init(m, &map);
	stray_error_clear(&err);
	dark_frame(pix, rows, 1, 0.1, &f);
	assert_int_equal(stray_dark_add(m, &f, hist, &err), STRAY_OK);
	assert_int_equal(stray_dark_add(m, &f, hist, &err), STRAY_OK);
	stray_dark_finish(m);
	assert_int_equal(stray_dark_find(m, 0.1 * (1 + 1e-9), &li, &err), 0);
	for (ch = 0; ch < 8; ch++) {
		double s0 = 0.0, s1 = 0.0, s2 = 0.0;
		size_t i;

		for (i = 0; i < ROWS * COLS; i++) {
			if (stray_bayer_channel(&map, (long)(i / COLS),
						(long)(i % COLS)) != ch ||
			    i == 0 || i == COLS + 1)
				continue;	/* the hot ones */
			s0 += 1.0;
			s1 += pix[i];
			s2 += (double)pix[i] * pix[i];
			if (ch == 0)
				naive += pix[i];
		}
		/* eq. 3.3: the level is the mean of the clean pixels */
		assert_near(m->lvl[li].mean[ch], s1 / s0, 1e-9);
		assert_near(m->lvl[li].var[ch], (s2 - s1 * s1 / s0) / (s0 - 1.0),
			    1e-9);
	}
	/* Averaging the hot pixel in would have cost 500/16 counts. */
	assert_true((naive + pix[0]) / 16.0 - m->lvl[li].mean[0] > 20.0);
	free(m);
}

static void test_dark_find_by_exposure(void **state)
{
	uint16_t pix[ROWS * COLS];
	long rows[ROWS];
	struct stray_bayer_map map;
	struct stray_dark_model *m = malloc(sizeof(*m));
	struct stray_frame f;
	struct stray_error err;
	size_t li, i;

	(void)state;
	stray_bayer_default(&map);
	stray_dark_init(m, &map);
	stray_error_clear(&err);
	for (i = 0; i < STRAY_DARK_LEVELS_MAX; i++) {
		dark_frame(pix, rows, 0, 0.01 * (double)(i + 1), &f);
		assert_int_equal(stray_dark_add(m, &f, hist, &err), STRAY_OK);
	}
	dark_frame(pix, rows, 0, 99.0, &f);
	assert_int_equal(stray_dark_add(m, &f, hist, &err), STRAY_ERANGE);
	stray_dark_finish(m);
	stray_error_clear(&err);
	assert_int_equal(stray_dark_find(m, 0.05, &li, &err), STRAY_OK);
	assert_int_equal(li, 4);
	assert_int_equal(stray_dark_find(m, 0.055, &li, &err), STRAY_ENOTFOUND);
	assert_string_equal(err.field, "EXPTIME");
	assert_near(err.value, 0.055, 1e-15);
	free(m);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_dark_levels_per_channel_ignore_hot),
		cmocka_unit_test(test_dark_find_by_exposure),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
