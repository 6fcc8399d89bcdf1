/*
 * test_response.c - the true response J = L_ful/(t1 nd1) - L_amb/(t2 nd2)
 * (thesis eq. 3.6) and its sums P (eq. 3.9), Pbar (eq. 3.13) and sigma
 * (eq. 3.14), against closed forms.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "stray/reduce_response.h"
#include "test_util.h"

#define ROWS 2
#define COLS 8
#define N (ROWS * COLS)

static uint32_t hist[STRAY_DARK_HIST_LEN];
static long rows[ROWS] = { 0, 1 };

struct fixture {
	struct stray_dark_model d;
	struct stray_accum full, amb;
	unsigned char mem[2][256];
	float j[N], var_j[N];
};

/* Darks at 0.1 s (level 100) and 0.2 s (level 120). */
static int setup(void **state)
{
	struct fixture *x = calloc(1, sizeof(*x));
	uint16_t pix[N];
	struct stray_frame f = { ROWS, COLS, pix, rows, 0, 0.1, 1.0, 1.0, 4095 };
	struct stray_bayer_map map;
	size_t i;

	stray_bayer_default(&map);
	stray_dark_init(&x->d, &map);
	for (i = 0; i < N; i++)
		pix[i] = 100;
	stray_dark_add(&x->d, &f, hist, NULL);
	for (i = 0; i < N; i++)
		pix[i] = 120;
	f.t_exp_s = 0.2;
	stray_dark_add(&x->d, &f, hist, NULL);
	stray_dark_finish(&x->d);
	stray_accum_init(&x->full, N, x->mem[0]);
	stray_accum_init(&x->amb, N, x->mem[1]);
	*state = x;
	return 0;
}

static int teardown(void **state)
{
	free(*state);
	return 0;
}

/* Two frames per group: counts base[i] -/+ 5. */
static void add_group(struct fixture *x, struct stray_accum *a,
		      const double *base, double t, double nd)
{
	uint16_t pix[N];
	struct stray_frame f = { ROWS, COLS, pix, rows, 0, t, nd, 1.0, 4095 };
	int k;
	size_t i;

	for (k = -1; k <= 1; k += 2) {
		for (i = 0; i < N; i++)
			pix[i] = (uint16_t)(base[i] + 5.0 * k);
		assert_int_equal(stray_accum_add(a, &x->d, &f, NULL), STRAY_OK);
	}
}

static void test_response_eq36_closed_form(void **state)
{
	struct fixture *x = *state;
	double full[N], amb[N], p = 0.0, s2 = 0.0, mean;
	struct stray_frame geo = { ROWS, COLS, NULL, rows, 0, 1, 1, 1, 4095 };
	struct stray_response_opts o = { 0 };
	struct stray_response_sums s;
	size_t i;

	for (i = 0; i < N; i++) {
		full[i] = 1100.0 + 40.0 * (double)(i % 3);	/* t1 = 0.1, nd 0.5 */
		amb[i] = 320.0;					/* t2 = 0.2, nd 1 */
	}
	add_group(x, &x->full, full, 0.1, 0.5);
	add_group(x, &x->amb, amb, 0.2, 1.0);
	assert_int_equal(stray_response_compute(&x->full, &x->amb, &x->d, NULL,
		&geo, &o, x->j, x->var_j, &s, NULL), STRAY_OK);
	for (i = 0; i < N; i++) {
		/* eq. 3.6 with the dark of each exposure (eq. 3.4-3.5) */
		double want = (full[i] - 100.0) / 0.05 - (amb[i] - 120.0) / 0.2;

		assert_near(x->j[i], want, 1e-2);
		/* 2 frames at -/+5: sample variance 50, of the mean 25;
		 * times the rate scales 1/(t nd) squared */
		assert_near(x->var_j[i], 25.0 / (0.05 * 0.05) +
			    25.0 / (0.2 * 0.2), 1e-1);
		p += want;
	}
	mean = p / N;
	for (i = 0; i < N; i++)
		s2 += (x->j[i] - mean) * (x->j[i] - mean);
	assert_near(s.power, p, 1e-6 * p);		/* eq. 3.9 */
	assert_near(s.mean, mean, 1e-6 * mean);	/* eq. 3.13 */
	assert_near(s.sigma, sqrt(s2 / N), 1e-3);	/* eq. 3.14 */
	assert_int_equal(s.n_valid, N);
}

static void test_response_masked_and_saturated_filled(void **state)
{
	struct fixture *x = *state;
	double full[N], amb[N];
	uint8_t mask[N] = { 0 };
	struct stray_frame geo = { ROWS, COLS, NULL, rows, 0, 1, 1, 1, 4095 };
	struct stray_response_sums s;
	size_t i;

	for (i = 0; i < N; i++) {
		full[i] = 200.0 + 10.0 * (double)(i % COLS);	/* a ramp */
		amb[i] = 150.0;
	}
	full[COLS + 5] = 5000.0;	/* saturated in both frames */
	add_group(x, &x->full, full, 0.1, 1.0);
	add_group(x, &x->amb, amb, 0.1, 1.0);
	mask[3] = STRAY_PIX_HOT;
	assert_int_equal(stray_response_compute(&x->full, &x->amb, &x->d, mask,
		&geo, NULL, x->j, x->var_j, &s, NULL), STRAY_OK);
	assert_int_equal(s.n_masked, 1);
	assert_int_equal(s.n_sat_pix, 1);
	assert_int_equal(s.n_valid, N - 2);
	/* Filled from the same colour 2 columns away: the ramp's value. */
	assert_near(x->j[3], (200.0 + 30.0 - 150.0) / 0.1, 1e-2);
	assert_near(x->j[COLS + 5], (200.0 + 50.0 - 150.0) / 0.1, 1e-2);
}

/* A pixel saturated in one of its two frames keeps one sample: the
 * variance of its mean is the single-frame variance pooled over the
 * pixels with repeats, while the rest of the frame (a usual row beside
 * it) keeps its own m2 / (n (n - 1)). */
static void test_response_single_sample_takes_pooled_variance(void **state)
{
	struct fixture *x = *state;
	double full[N], amb[N];
	struct stray_frame geo = { ROWS, COLS, NULL, rows, 0, 1, 1, 1, 4095 };
	struct stray_response_sums s;
	size_t i, one = COLS + 2;	/* row 1: 4090 kept, 4100 saturated */

	for (i = 0; i < N; i++) {
		full[i] = 1100.0;	/* t 0.1, nd 0.5: rate scale 20 */
		amb[i] = 320.0;		/* t 0.2, nd 1: rate scale 5 */
	}
	full[one] = 4095.0;
	add_group(x, &x->full, full, 0.1, 0.5);
	add_group(x, &x->amb, amb, 0.2, 1.0);
	assert_int_equal(x->full.n[one], 1);
	assert_int_equal(stray_response_compute(&x->full, &x->amb, &x->d, NULL,
		&geo, NULL, x->j, x->var_j, &s, NULL), STRAY_OK);
	assert_int_equal(s.n_valid, N);
	for (i = 0; i < N; i++) {
		/* -/+5 counts: m2 = 50, of the mean 25 (n = 2), single
		 * frame 50 (pooled), times the scale squared */
		double want = (i == one ? 50.0 : 25.0) * 400.0 + 25.0 * 25.0;

		assert_near(x->var_j[i], want, 1e-6 * want);
	}
	assert_near(x->j[one], (4090.0 - 100.0) * 20.0 - (320.0 - 120.0) * 5.0,
		    1e-2);
}

static void test_response_row_filter_and_profile(void **state)
{
	struct fixture *x = *state;
	double full[N], amb[N], prof[COLS], vprof[COLS];
	struct stray_frame geo = { ROWS, COLS, NULL, rows, 0, 1, 1, 1, 4095 };
	struct stray_response_opts o = { 1 };
	struct stray_response_sums s;
	size_t i;

	for (i = 0; i < N; i++) {
		full[i] = i % COLS == 4 ? 400.0 : 200.0;	/* one spike */
		amb[i] = 100.0;
	}
	add_group(x, &x->full, full, 0.1, 1.0);
	add_group(x, &x->amb, amb, 0.1, 1.0);
	assert_int_equal(stray_response_compute(&x->full, &x->amb, &x->d, NULL,
		&geo, &o, x->j, x->var_j, &s, NULL), STRAY_OK);
	/* 3-pixel row mean: the spike spread over columns 3..5 */
	assert_near(x->j[4], (1000.0 + 3000.0 + 1000.0) / 3.0, 1e-2);
	assert_near(x->j[3], (1000.0 + 1000.0 + 3000.0) / 3.0, 1e-2);
	assert_near(x->j[0], 1000.0, 1e-2);
	stray_response_profile(x->j, x->var_j, ROWS, COLS, prof, vprof);
	assert_near(prof[4], x->j[4], 1e-3);
	assert_near(vprof[0], (x->var_j[0] + x->var_j[COLS]) / 4.0, 1e-3);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_response_eq36_closed_form,
						setup, teardown),
		cmocka_unit_test_setup_teardown(
			test_response_masked_and_saturated_filled, setup,
			teardown),
		cmocka_unit_test_setup_teardown(
			test_response_single_sample_takes_pooled_variance,
			setup, teardown),
		cmocka_unit_test_setup_teardown(
			test_response_row_filter_and_profile, setup, teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
