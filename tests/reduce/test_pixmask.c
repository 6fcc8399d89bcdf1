/*
 * test_pixmask.c - hot and dead pixels found from the darks (thesis
 * §3.2): the per-pixel dark excess against the robust spread.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "stray/reduce_dark.h"
#include "test_util.h"

#define ROWS 16
#define COLS 32
#define N (ROWS * COLS)

static uint32_t hist[STRAY_DARK_HIST_LEN];

/* A deterministic pseudo-normal deviate (sum of 12 uniforms - 6). */
static double noise(unsigned *s)
{
	double v = 0.0;
	int k;

	for (k = 0; k < 12; k++) {
		*s = *s * 1103515245u + 12345u;
		v += (double)((*s >> 8) & 0xffff) / 65536.0;
	}
	return v - 6.0;
}

/* Level 100 + 4 sigma noise; hot pixel 7 (+60); pixel 9 dead (0);
 * pixel 11 stuck at the level (no temporal noise). */
static void frame(uint16_t *pix, unsigned *s)
{
	size_t i;

	for (i = 0; i < N; i++)
		pix[i] = (uint16_t)lround(100.0 + 4.0 * noise(s));
	pix[7] += 60;
	pix[9] = 0;
	pix[11] = 100;
}

static void run(int n_frames, uint8_t *mask, struct stray_mask_stats *st,
		int *rc)
{
	static uint16_t pix[N];
	static double mean[N], m2[N], scratch[N];
	long rows[ROWS];
	struct stray_bayer_map map;
	struct stray_dark_model *m = malloc(sizeof(*m));
	struct stray_pixstat ps;
	struct stray_frame f = { ROWS, COLS, pix, rows, 0, 0.1, 1.0, 1.0, 4095 };
	struct stray_error err;
	unsigned s = 5;
	int k;

	for (k = 0; k < ROWS; k++)
		rows[k] = k;
	stray_bayer_default(&map);
	stray_dark_init(m, &map);
	stray_error_clear(&err);
	for (k = 0; k < n_frames; k++) {	/* pass 1 */
		frame(pix, &s);
		assert_int_equal(stray_dark_add(m, &f, hist, &err), STRAY_OK);
	}
	stray_dark_finish(m);
	stray_pixstat_init(&ps, N, mean, m2);
	for (k = 0, s = 5; k < n_frames; k++) {	/* pass 2, same frames */
		frame(pix, &s);
		assert_int_equal(stray_pixstat_add(&ps, m, &f, &err), STRAY_OK);
	}
	*rc = stray_mask_build(&ps, 6.0, mask, scratch, st, &err);
	free(m);
}

static void test_mask_finds_hot_dead_stuck(void **state)
{
	uint8_t mask[N];
	struct stray_mask_stats st;
	size_t i;
	int rc;

	(void)state;
	run(6, mask, &st, &rc);
	assert_int_equal(rc, STRAY_OK);
	for (i = 0; i < N; i++)
		assert_int_equal(mask[i], i == 7 ? STRAY_PIX_HOT :
				 i == 9 || i == 11 ? STRAY_PIX_DEAD : STRAY_PIX_OK);
	assert_int_equal(st.n_hot, 1);
	assert_int_equal(st.n_dead, 2);
	/* The spread of a 6-frame mean of 4-count noise: 4/sqrt(6). */
	assert_near(st.excess_sigma, 4.0 / sqrt(6.0), 0.3);
}

static void test_mask_needs_two_darks(void **state)
{
	uint8_t mask[N];
	struct stray_mask_stats st;
	int rc;

	(void)state;
	run(1, mask, &st, &rc);
	assert_int_equal(rc, STRAY_EINVAL);
}

static int by_value(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* The median as the textbook defines it: sort, take the middle (or the
 * mean of the middle two). */
static double sorted_median(double *v, size_t n)
{
	qsort(v, n, sizeof(*v), by_value);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The median and MAD of mask_build against a sort, on values built to
 * stress a radix selection: both signs, zeros, many ties, magnitudes
 * from 1e-300 to 1e300, the middle two in different buckets; odd and
 * even counts. */
static void test_mask_median_is_exact(void **state)
{
	static double mean[2 * N + 1], m2[2 * N + 1], scratch[2 * N + 1];
	static double sorted[2 * N + 1];
	static uint8_t mask[2 * N + 1];
	unsigned seed = 7;
	size_t n, i;
	int trial;

	(void)state;
	for (trial = 0; trial < 40; trial++) {
		n = trial % 2 ? 2 * N : 2 * N + 1 - (size_t)(trial % 7);
		for (i = 0; i < n; i++) {
			double u = noise(&seed);

			switch ((trial + i) % 5) {
			case 0: mean[i] = floor(u * 4.0) / 4.0; break;
			case 1: mean[i] = u * pow(10.0, trial * 15 - 300); break;
			case 2: mean[i] = trial % 3 ? 0.0 : -u; break;
			case 3: mean[i] = 3.0 + (trial % 4) * u; break;
			default: mean[i] = -1.0 / (1.0 + u * u); break;
			}
			m2[i] = 1.0;
		}
		if (trial == 39) {	/* the middle two far apart */
			for (i = 0; i < n; i++)
				mean[i] = i < n / 2 ? -1e200 : 1e-200;
		}
		{
			struct stray_pixstat s = { n, mean, m2, 2 };
			struct stray_mask_stats st;
			double med, mad;

			for (i = 0; i < n; i++)
				sorted[i] = mean[i];
			med = sorted_median(sorted, n);
			for (i = 0; i < n; i++)
				sorted[i] = fabs(mean[i] - med);
			mad = fmax(1.4826 * sorted_median(sorted, n), 0.25);
			assert_int_equal(stray_mask_build(&s, 6.0, mask,
							  scratch, &st, NULL),
					 STRAY_OK);
			assert_true(st.excess_median == med);
			assert_true(st.excess_sigma == mad);
		}
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_mask_finds_hot_dead_stuck),
		cmocka_unit_test(test_mask_needs_two_darks),
		cmocka_unit_test(test_mask_median_is_exact),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
