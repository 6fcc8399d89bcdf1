/*
 * test_common.c - noise common to a whole frame (reduce_common.h) and
 * visits carried from the stage's read-back angle to the commanded one
 * (reduce_angle.h).  The frames here are made with a known per-frame
 * scale (a monitor reading off the true lamp) and known pixel noise; the
 * estimator must find the former and not the latter, and must not take a
 * known drift for noise.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/reduce_angle.h"
#include "stray/reduce_common.h"
#include "test_util.h"

#define ROWS 32
#define COLS 64
#define NPIX (ROWS * COLS)
#define GROUPS 150
#define REPEATS 3

static uint32_t hist[STRAY_DARK_HIST_LEN];
static long det_rows[ROWS];

struct rng {
	uint64_t s;
};

static double uniform(struct rng *r)
{
	uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);

	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	z ^= z >> 31;
	return ((z >> 11) + 0.5) / 9007199254740992.0;
}

static double normal(struct rng *r)
{
	return sqrt(-2.0 * log(uniform(r))) * cos(6.283185307179586 *
						  uniform(r));
}

/* Dark level 100 DN in every channel at t = 0.1 s. */
static struct stray_dark_model *flat_dark(void)
{
	static uint16_t pix[NPIX];
	struct stray_bayer_map map;
	struct stray_dark_model *m = malloc(sizeof(*m));
	struct stray_frame f = { ROWS, COLS, pix, det_rows, 0, 0.1, 1.0, 1.0,
				 4095 };
	size_t i;

	for (i = 0; i < ROWS; i++)
		det_rows[i] = (long)i;
	for (i = 0; i < NPIX; i++)
		pix[i] = 100;
	stray_bayer_default(&map);
	stray_dark_init(m, &map);
	assert_int_equal(stray_dark_add(m, &f, hist, NULL), STRAY_OK);
	stray_dark_finish(m);
	return m;
}

/* Close a group as the sweep does: its accumulator's variance sums. */
static void finish(struct stray_common_group *g, const struct stray_accum *a,
		   const uint8_t *mask)
{
	struct stray_accum_var v;

	stray_accum_var_sums(a, mask, &v);
	stray_common_group_finish(g, &v);
}

/*
 * GROUPS groups of REPEATS frames, 100 places apart in the order x: light
 * 1000 DN x (1 + drift x_k), pixel noise 3 DN, each frame's MONITOR off the true lamp by a relative
 * normal error rel_sigma.  Returns the pooled s^2 with beta taken out.
 */
static double pooled(double rel_sigma, double drift, double beta,
		     size_t *dof_sum)
{
	struct stray_dark_model *d = flat_dark();
	static uint16_t pix[NPIX];
	static double est[GROUPS], ind[GROUPS];
	static size_t dof[GROUPS];
	struct stray_frame f = { ROWS, COLS, pix, det_rows, 0, 0.1, 1.0, 1.0,
				 4095 };
	struct stray_accum a;
	struct stray_common_group g;
	struct rng r = { 42 };
	void *mem = malloc(stray_accum_bytes(NPIX));
	size_t k, i, n;
	double s2;

	*dof_sum = 0;
	for (k = 0; k < GROUPS; k++) {
		stray_accum_init(&a, NPIX, mem);
		stray_common_group_reset(&g);
		for (n = 0; n < REPEATS; n++) {
			double x = (double)(k * 300 + n * 100);
			double lamp = 1.0 + drift * x;

			for (i = 0; i < NPIX; i++)
				pix[i] = (uint16_t)lround(100.0 + 1000.0 *
					lamp + 3.0 * normal(&r));
			f.monitor = 1.0 + rel_sigma * normal(&r);
			assert_int_equal(stray_accum_add(&a, d, &f, NULL),
					 STRAY_OK);
			assert_int_equal(stray_common_group_add(&g, d, &f,
					 NULL, x, NULL), STRAY_OK);
		}
		finish(&g, &a, NULL);
		/* the mean total: 1000 DN / 0.1 s per pixel, drifted */
		assert_true(fabs(stray_common_group_mean(&g) / (1e4 * NPIX *
			(1.0 + drift * (double)(k * 300 + 100))) - 1.0) < 0.01);
		dof[k] = stray_common_group_stats(&g, beta, &est[k], &ind[k]);
		*dof_sum += dof[k];
	}
	s2 = stray_common_fit(est, ind, dof, GROUPS);
	free(mem);
	free(d);
	return s2;
}

static void test_common_noise_found(void **state)
{
	size_t dof;
	double s2 = pooled(1e-3, 0.0, 0.0, &dof);

	(void)state;
	assert_int_equal(dof, GROUPS * (REPEATS - 1));
	print_message("monitor noise 1e-3: measured %.4g\n", sqrt(s2));
	/* 300 dof: the variance to about 8 % (1 sigma) */
	assert_true(fabs(sqrt(s2) / 1e-3 - 1.0) < 0.12);
}

static void test_pixel_noise_not_common(void **state)
{
	size_t dof;
	double s2 = pooled(0.0, 0.0, 0.0, &dof);

	(void)state;
	print_message("no monitor noise: measured %.3g\n", sqrt(s2));
	/* pixel noise alone: 3 DN / sqrt(2048) on 1000 DN, 6.6e-5 per frame
	 * total; none of it may be taken as common */
	assert_true(sqrt(s2) < 2e-5);
}

static void test_known_drift_not_noise(void **state)
{
	size_t dof;
	double left = pooled(0.0, 1e-6, 0.0, &dof);
	double out = pooled(0.0, 1e-6, 1e-6, &dof);

	(void)state;
	/* 1e-4 a frame, 4.5 % over the sweep (as a lamp drifts) */
	print_message("drift 1e-4 per frame: %.3g left in, %.3g taken out\n",
		      sqrt(left), sqrt(out));
	assert_true(sqrt(left) > 0.8e-4);	/* the trend is there... */
	assert_true(sqrt(out) < 2e-5);		/* ...and removed */
}

static void test_group_saturated_unusable(void **state)
{
	struct stray_dark_model *d = flat_dark();
	static uint16_t pix[NPIX];
	struct stray_frame f = { ROWS, COLS, pix, det_rows, 0, 0.1, 1.0, 1.0,
				 4095 };
	struct stray_accum a;
	struct stray_common_group g;
	void *mem = malloc(stray_accum_bytes(NPIX));
	double est, ind;
	int n;

	(void)state;
	stray_accum_init(&a, NPIX, mem);
	stray_common_group_reset(&g);
	for (n = 0; n < 3; n++) {
		memset(pix, 0, sizeof(pix));
		pix[5] = n == 1 ? 4095 : 2000;
		assert_int_equal(stray_accum_add(&a, d, &f, NULL), STRAY_OK);
		assert_int_equal(stray_common_group_add(&g, d, &f, NULL, n,
							NULL), STRAY_OK);
	}
	finish(&g, &a, NULL);
	assert_int_equal(stray_common_group_stats(&g, 0.0, &est, &ind), 0);
	free(mem);
	free(d);
}

/* alpha = exp(-theta / 6): visits taken 0.01 deg past their angle. */
/*
 * The frame totals and the pixels' own variance against sums written out
 * here pixel by pixel: masked pixels are left out of both, a pixel with
 * one saturated sample keeps its other two, and a saturated sample only
 * makes the group incomplete where the mask keeps the pixel.
 */
static void test_totals_and_pixel_variance_closed_form(void **state)
{
	struct stray_dark_model *d = flat_dark();
	static uint16_t pix[3][NPIX];
	static uint8_t mask[NPIX];
	struct stray_frame f = { ROWS, COLS, NULL, det_rows, 0, 0.1, 1.0, 1.0,
				 4095 };
	struct stray_accum a;
	struct stray_common_group g, masked_only;
	void *mem = malloc(stray_accum_bytes(NPIX));
	double total0 = 0.0, v_ind = 0.0, m2_all = 0.0, dof_all = 0.0;
	struct stray_accum_var v;
	size_t i, k, sat = 5 * COLS + 9, hidden = 7 * COLS + 3;

	(void)state;
	for (k = 0; k < 3; k++)
		for (i = 0; i < NPIX; i++)
			pix[k][i] = (uint16_t)(300 + i * 7 % 13 +
					       5 * k * (i % 3));
	for (i = 0; i < NPIX; i += 37)
		mask[i] = STRAY_PIX_HOT;
	mask[hidden] = STRAY_PIX_DEAD;
	pix[2][sat] = 4095;		/* saturated once, kept */
	stray_accum_init(&a, NPIX, mem);
	stray_common_group_reset(&g);
	for (k = 0; k < 3; k++) {
		f.pix = pix[k];
		assert_int_equal(stray_accum_add(&a, d, &f, NULL), STRAY_OK);
		assert_int_equal(stray_common_group_add(&g, d, &f, mask,
			(double)k, NULL), STRAY_OK);
	}
	finish(&g, &a, mask);
	stray_accum_var_sums(&a, mask, &v);
	for (i = 0; i < NPIX; i++) {
		double x[3], mean = 0.0, ss = 0.0;
		size_t n = 0;

		for (k = 0; k < 3; k++)
			if (pix[k][i] < 4095)
				x[n++] = (pix[k][i] - 100.0) / 0.1;
		for (k = 0; k < n; k++)
			mean += x[k] / (double)n;
		for (k = 0; k < n; k++)
			ss += (x[k] - mean) * (x[k] - mean);
		m2_all += ss;		/* masked or not: the pooled sums */
		dof_all += (double)(n - 1);
		if (mask[i] != STRAY_PIX_OK)
			continue;
		total0 += (pix[0][i] - 100.0) / 0.1;
		v_ind += ss / (double)(n - 1);
	}
	assert_int_equal(a.n[sat], 2);
	assert_near(g.s0, total0, 1e-9 * total0);	/* frame 0's total */
	assert_near(g.v_ind, v_ind, 1e-5 * v_ind);
	assert_near(v.m2, m2_all, 1e-5 * m2_all);
	assert_true(v.dof == dof_all);
	assert_int_equal(g.incomplete, 1);
	/* saturated samples under the mask, one in each column phase: the
	 * group stays complete */
	for (k = 0; k < 4; k++) {
		mask[sat + k] = STRAY_PIX_HOT;
		pix[2][sat + k] = 4095;
	}
	stray_common_group_reset(&masked_only);
	f.pix = pix[2];
	assert_int_equal(stray_common_group_add(&masked_only, d, &f, mask, 0.0,
						NULL), STRAY_OK);
	assert_int_equal(masked_only.incomplete, 0);
	free(mem);
	free(d);
}

/* Rows wider than the pieces the sums walk in (4096 columns), without a
 * mask and with an all-clear one: the same totals, and the ones written
 * out here. */
static void test_wide_rows_without_mask(void **state)
{
	enum { WR = 2, WC = 4102, WN = WR * WC };
	struct stray_dark_model *d = flat_dark();
	static uint16_t pix[3][WN];
	static uint8_t clear[WN];
	static long wrows[WR] = { 0, 1 };
	struct stray_frame f = { WR, WC, NULL, wrows, 0, 0.1, 1.0, 1.0, 4095 };
	struct stray_accum a;
	struct stray_common_group none, all;
	void *mem = malloc(stray_accum_bytes(WN));
	double total0 = 0.0, v_ind = 0.0;
	size_t i, k;

	(void)state;
	for (k = 0; k < 3; k++)
		for (i = 0; i < WN; i++)
			pix[k][i] = (uint16_t)(400 + i % 11 + 3 * k * (i % 2));
	stray_accum_init(&a, WN, mem);
	stray_common_group_reset(&none);
	stray_common_group_reset(&all);
	for (k = 0; k < 3; k++) {
		f.pix = pix[k];
		assert_int_equal(stray_accum_add(&a, d, &f, NULL), STRAY_OK);
		assert_int_equal(stray_common_group_add(&none, d, &f, NULL,
			(double)k, NULL), STRAY_OK);
		assert_int_equal(stray_common_group_add(&all, d, &f, clear,
			(double)k, NULL), STRAY_OK);
	}
	finish(&none, &a, NULL);
	finish(&all, &a, clear);
	for (i = 0; i < WN; i++) {
		double d1 = 3.0 * (double)(i % 2) / 0.1;	/* steps */

		total0 += (pix[0][i] - 100.0) / 0.1;
		v_ind += d1 * d1;	/* x0, x0 + d, x0 + 2d: ss / 2 */
	}
	assert_true(none.s0 == all.s0);
	assert_true(none.v_ind == all.v_ind);
	assert_near(none.s0, total0, 1e-12 * total0);
	assert_near(none.v_ind, v_ind, 1e-5 * v_ind);
	free(mem);
	free(d);
}

static void test_read_back_carried_to_commanded(void **state)
{
	struct stray_curve_point p[11];
	struct stray_visit v[11];
	double rb[11], worst;
	size_t i;

	(void)state;
	memset(p, 0, sizeof(p));
	memset(v, 0, sizeof(v));
	for (i = 0; i < 11; i++) {
		p[i].theta_deg = v[i].theta_deg = (double)i;
		rb[i] = i ? (double)i + 0.01 : -0.005;
		p[i].alpha = exp(-fabs(rb[i]) / 6.0);
		v[i].power = 5.0 * exp(-fabs(rb[i]) / 6.0);
		v[i].var_power = 1e-6 * v[i].power * v[i].power;
	}
	assert_near(stray_curve_log_slope(p, 11, 5), -1.0 / 6.0, 1e-9);
	worst = stray_visits_to_commanded(v, 11, rb, p, 11);
	assert_near(worst, 0.01, 1e-12);
	for (i = 0; i < 11; i++) {
		double want = 5.0 * exp(-(double)i / 6.0);

		/* the curve's own slope, at most 1e-6 off */
		assert_true(fabs(v[i].power / want - 1.0) < 1e-5);
		assert_near(v[i].var_power / (v[i].power * v[i].power), 1e-6,
			    1e-12);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_common_noise_found),
		cmocka_unit_test(test_pixel_noise_not_common),
		cmocka_unit_test(test_known_drift_not_noise),
		cmocka_unit_test(test_group_saturated_unusable),
		cmocka_unit_test(test_totals_and_pixel_variance_closed_form),
		cmocka_unit_test(test_wide_rows_without_mask),
		cmocka_unit_test(test_read_back_carried_to_commanded),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
