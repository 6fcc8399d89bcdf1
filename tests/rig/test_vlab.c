/*
 * test_vlab.c - the virtual lab against closed forms: dark level per
 * Bayer channel (bias + dark rate x t), photon-transfer variance (read^2
 * + signal/gain: the gain is recovered from the frames alone), hot pixel
 * rate, saturation, lamp drift, lens alpha(0) = 1 (eq. 3.12) and the
 * ghost's column moving with theta.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rig/vlab.h"

#define NR 16
#define NC 512
#define NPX (NR * NC)

static uint16_t rows[NR];

static int setup(void **state)
{
	int r;

	(void)state;
	for (r = 0; r < NR; r++)
		rows[r] = (uint16_t)(900 + r);
	return 0;
}

static void render(const struct rig_vlab_cfg *c, int lit, double t,
		   double t_lab_s, uint64_t seed, uint16_t *px)
{
	struct rig_vlab_state st = { 0, t, 1.0, t_lab_s, 1, 0, lit };

	rig_vlab_render(c, &st, rows, NR, 1000, NC, seed, px);
}

static void test_vlab_dark_level_per_channel(void **state)
{
	static uint16_t px[NPX];
	struct rig_vlab_cfg c;
	double sum[RIG_VLAB_CHANNELS] = { 0 };
	int n[RIG_VLAB_CHANNELS] = { 0 }, i, ch;

	(void)state;
	rig_vlab_defaults(&c);
	c.hot_frac = 0;
	render(&c, 0, 1.0, 0, 1, px);
	for (i = 0; i < NPX; i++) {
		ch = rig_vlab_channel(rows[i / NC], 1000 + i % NC);
		sum[ch] += px[i];
		n[ch]++;
	}
	for (ch = 0; ch < RIG_VLAB_CHANNELS; ch++) {
		/* D = bias + dark x t; sigma of the mean ~ 1.8/32 DN. */
		double want = c.bias_dn[ch] + c.dark_dn_s * 1.0;

		assert_int_equal(n[ch], NPX / 8);
		assert_float_equal(sum[ch] / n[ch], want, 0.3);
	}
}

/* Photon transfer: var(A - B)/2 = read^2 + S/gain + 1/12 for two frames
 * of the same light S (DN); the gain is solved for and compared. */
static void test_vlab_photon_transfer_gives_gain(void **state)
{
	static uint16_t a[NPX], b[NPX];
	struct rig_vlab_cfg c;
	double mean = 0, var = 0, signal, gain;
	int i;

	(void)state;
	rig_vlab_defaults(&c);
	c.hot_frac = 0;
	c.gradient = 0;
	c.n_ghosts = 0;
	c.lamp_rate_dn_s = 2000;
	render(&c, 1, 1.0, 0, 11, a);
	render(&c, 1, 1.0, 0, 12, b);
	for (i = 0; i < NPX; i++)
		mean += 0.5 * (a[i] + b[i]);
	mean /= NPX;
	for (i = 0; i < NPX; i++) {
		double d = (double)a[i] - b[i];

		var += d * d;
	}
	var /= 2.0 * NPX;
	signal = mean - 102.125;	/* mean of the 8 default biases */
	gain = signal / (var - c.read_noise_dn * c.read_noise_dn - 1 / 12.0);
	assert_float_equal(gain, c.gain_e_per_dn, 0.1);
}

static void test_vlab_hot_pixels_fixed_and_counted(void **state)
{
	static uint16_t a[NPX], b[NPX];
	struct rig_vlab_cfg c;
	int i, hot_a = 0, both = 0;

	(void)state;
	rig_vlab_defaults(&c);
	c.hot_frac = 0.01;
	render(&c, 0, 1.0, 0, 1, a);
	render(&c, 0, 1.0, 0, 2, b);
	for (i = 0; i < NPX; i++) {
		int ha = a[i] > 200, hb = b[i] > 200;

		hot_a += ha;
		both += ha && hb;
	}
	/* Binomial: 81.9 expected, sd 9. */
	assert_in_range(hot_a, 50, 115);
	assert_int_equal(both, hot_a);	/* the same pixels every frame */
}

static void test_vlab_saturates_at_satlevel(void **state)
{
	static uint16_t px[NPX];
	struct rig_vlab_cfg c;
	int i;

	(void)state;
	rig_vlab_defaults(&c);
	render(&c, 1, 1.0, 0, 3, px);	/* 4e5 DN/s for 1 s, no ND */
	for (i = 0; i < NPX; i++)
		assert_int_equal(px[i], 4095);
}

static void test_vlab_lamp_drift(void **state)
{
	static uint16_t a[NPX], b[NPX];
	struct rig_vlab_cfg c;
	double sa = 0, sb = 0;
	int i;

	(void)state;
	rig_vlab_defaults(&c);
	c.hot_frac = 0;
	c.lamp_drift_per_h = 0.1;
	c.lamp_rate_dn_s = 3000;
	render(&c, 1, 1.0, 0, 5, a);
	render(&c, 1, 1.0, 3600, 6, b);
	for (i = 0; i < NPX; i++) {
		sa += a[i] - 102.125 - c.dark_dn_s;
		sb += b[i] - 102.125 - c.dark_dn_s;
	}
	assert_float_equal(sb / sa, 1.1, 0.01);
}

static void test_vlab_lens_alpha_and_ghost(void **state)
{
	struct rig_vlab_cfg c;
	const struct rig_ghost *g;
	double best = 0, a_prev = 2;
	int col, best_col = -1, theta;

	(void)state;
	rig_vlab_defaults(&c);
	assert_float_equal(rig_vlab_lens_alpha(&c, 0, rows, NR, 0, 2592), 1.0,
			   1e-12);
	c.n_ghosts = 0;
	for (theta = 0; theta <= 45; theta += 5) {
		double a = rig_vlab_lens_alpha(&c, theta, rows, NR, 0, 2592);

		assert_true(a < a_prev);
		a_prev = a;
	}
	rig_vlab_defaults(&c);
	c.gradient = 0;
	c.ghost[0].amp = 0.05;
	g = &c.ghost[0];
	for (col = 0; col < 2592; col++) {
		double r = rig_vlab_direct_rate(&c, g->theta_c_deg, 960, col);

		if (r > best) {
			best = r;
			best_col = col;
		}
	}
	assert_int_equal(best_col, (int)lround(g->col_at0 + g->px_per_deg *
					       g->theta_c_deg));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup(test_vlab_dark_level_per_channel, setup),
		cmocka_unit_test_setup(test_vlab_photon_transfer_gives_gain,
				       setup),
		cmocka_unit_test_setup(test_vlab_hot_pixels_fixed_and_counted,
				       setup),
		cmocka_unit_test_setup(test_vlab_saturates_at_satlevel, setup),
		cmocka_unit_test_setup(test_vlab_lamp_drift, setup),
		cmocka_unit_test_setup(test_vlab_lens_alpha_and_ghost, setup),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
