/*
 * test_frame.c - one frame's flags and false stars against ground libstray
 * (thesis eq. 2.18, fig. 2.7, fig. 5.1): exclusion flags where
 * stray_exclusion_angle says, FDR as stray_fdr_rate says, hysteresis that
 * stops chatter, eclipse, lunar phase, Earth, and invalid inputs.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fdrfw/earth.h"
#include "fdrfw/ephem.h"
#include "fdrfw/fdrfw.h"
#include "fdrfw/vec.h"
#include "fixture.h"
#include "stray/fdr.h"
#include "stray/photometry.h"
#include "stray/sensor.h"

#define DEG 0.017453292519943295

static struct fdrfw_table table;

static int setup(void **state)
{
	(void)state;
	fixture_table(&table);
	return 0;
}

/* Boresight +z (identity attitude); Sun at theta in the y-z plane; Moon
 * along +x (90 deg off); spacecraft 7000 km out along +z, so the Earth is
 * behind the sensor and the Sun is not eclipsed. */
static void frame_with_sun_at(struct fdrfw_input *in, double theta_deg,
			      float t_exp_s)
{
	memset(in, 0, sizeof(*in));
	in->q[0] = 1.0f;
	in->t_exp_s = t_exp_s;
	in->pos_km[2] = 7000.0f;
	in->use_given_dirs = 1;
	in->sun_dir[1] = (float)sin(theta_deg * DEG);
	in->sun_dir[2] = (float)cos(theta_deg * DEG);
	in->moon_dir[0] = 1.0f;
}

/* Ground truth: the Sun's model, alpha_req and exclusion angle, double. */
static void ground_sun(double t_exp_s, struct stray_fdr_model *m,
		       double *theta_x)
{
	double req;
	struct stray_error err;

	stray_error_clear(&err);
	stray_sensor_fdr_model(stray_sensor_st16_like(), fixture_fluxes()->sun,
			       fixture_fluxes()->drs, m);
	m->t_exp_s = t_exp_s;
	assert_int_equal(stray_fdr_alpha_required(m, 5.0, &req, &err), 0);
	assert_int_equal(stray_exclusion_angle(fixture_curve(), req, theta_x,
					       &err), 0);
}

static void check_sun_sweep(float t_exp_s)
{
	struct stray_fdr_model m;
	double theta_x, th;
	int n = 0;

	ground_sun(t_exp_s, &m, &theta_x);
	printf("t_exp %.3f s: ground exclusion angle %.3f deg\n",
	       (double)t_exp_s, theta_x);
	for (th = 0.3; th < 84.0; th += 0.173) {
		struct fdrfw_ctx ctx;
		struct fdrfw_input in;
		struct fdrfw_output out;
		double fdr;

		assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
		frame_with_sun_at(&in, th, t_exp_s);
		assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
		assert_near(out.theta_deg[FDRFW_SUN], th, 1e-4);
		assert_int_equal(stray_fdr_rate(&m,
			stray_curve_alpha_at(fixture_curve(), th), &fdr, NULL), 0);
		if (fdr > 1e-30)
			assert_near(out.false_stars[FDRFW_SUN], fdr, 1e-3 * fdr);
		if (fabs(th - theta_x) > 0.01) {
			assert_int_equal((out.flags & FDRFW_SUN_EXCLUDED) != 0,
					 th < theta_x);
			n++;
		}
	}
	assert_true(n > 400);
}

static void test_sun_flag_matches_exclusion_angle(void **state)
{
	(void)state;
	check_sun_sweep(table.t_exp_nominal_s);	/* threshold from table */
	check_sun_sweep(0.02f);		/* threshold recomputed on board */
	check_sun_sweep(0.5f);
}

/* A Sun wandering +-0.2 deg about its exclusion angle while drifting out:
 * one clear, no chatter; with the margin set to 0 the same path chatters
 * (so the test can tell). */
static int count_toggles(const struct fdrfw_table *t, double theta_x)
{
	struct fdrfw_ctx ctx;
	uint32_t prev = FDRFW_SUN_EXCLUDED;
	int i, toggles = 0;

	assert_int_equal(fdrfw_init(&ctx, t), FDRFW_OK);
	for (i = 0; i <= 400; i++) {
		struct fdrfw_input in;
		struct fdrfw_output out;
		double th = theta_x - 1.0 + 0.005 * i + 0.2 * sin(i * 1.3);

		frame_with_sun_at(&in, th, t->t_exp_nominal_s);
		assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
		if ((out.flags & FDRFW_SUN_EXCLUDED) != prev) {
			toggles++;
			if (prev)	/* cleared: only past the margin */
				assert_true(th >= theta_x +
					    t->hysteresis_deg - 0.01);
		}
		prev = out.flags & FDRFW_SUN_EXCLUDED;
	}
	assert_int_equal(prev, 0);	/* it ends well outside */
	return toggles;
}

static void test_hysteresis_no_chatter(void **state)
{
	struct stray_fdr_model m;
	struct fdrfw_table bare = table;
	double theta_x;

	(void)state;
	ground_sun(table.t_exp_nominal_s, &m, &theta_x);
	assert_int_equal(count_toggles(&table, theta_x), 1);
	bare.hysteresis_deg = 0.0f;
	fdrfw_table_seal(&bare);
	assert_true(count_toggles(&bare, theta_x) > 3);
}

static void test_eclipse(void **state)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	frame_with_sun_at(&in, 5.0, 0.1f);	/* Sun in the field ... */
	in.pos_km[2] = -7000.0f;		/* ... but behind the Earth */
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	assert_true(out.flags & FDRFW_SUN_ECLIPSED);
	assert_false(out.flags & FDRFW_SUN_EXCLUDED);
	assert_true(out.false_stars[FDRFW_SUN] == 0.0f);
	/* Pointing at the dark Earth: in the field, no light from it. */
	assert_true(out.flags & FDRFW_EARTH_IN_FOV);
	assert_true(out.false_stars[FDRFW_EARTH] == 0.0f);
	assert_false(out.flags & FDRFW_EARTH_EXCLUDED);
}

/* The Moon's false stars follow libstray's phase law; in the field it is
 * excluded (thesis §5.1: it saturates the detector). */
static void test_moon_phase_and_field(void **state)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output full, half;
	double dm, m_full = (double)table.moon_full_mag;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	frame_with_sun_at(&in, 0.0, 0.1f);
	in.sun_dir[1] = 0.0f;	/* Sun along -z: full Moon on axis */
	in.sun_dir[2] = -1.0f;
	in.moon_dir[0] = 0.0f;
	in.moon_dir[2] = 1.0f;
	in.pos_km[2] = 0.0f;
	in.pos_km[0] = 7000.0f;	/* Earth along -x, out of the way */
	assert_int_equal(fdrfw_frame(&ctx, &in, &full), FDRFW_OK);
	assert_near(full.moon_phase_deg, 0.0, 1e-3);
	assert_true(full.flags & FDRFW_MOON_IN_FOV);
	assert_true(full.flags & FDRFW_MOON_EXCLUDED);
	in.sun_dir[2] = 0.0f;	/* Sun along +y: quarter Moon */
	in.sun_dir[1] = 1.0f;
	assert_int_equal(fdrfw_frame(&ctx, &in, &half), FDRFW_OK);
	assert_near(half.moon_phase_deg, 90.0, 1e-3);
	dm = stray_moon_mag_at_phase(m_full, 90.0) - m_full;
	/* Moon on axis: alpha = 1, so I_px scales with the flux; compare
	 * the variance-ratio through eq. 2.3 in the ln FDR slope instead of
	 * the (saturated) rate: both runs are evaluated by libstray. */
	{
		struct stray_fdr_model m;
		double lf, lh, i_sdt;

		stray_sensor_fdr_model(stray_sensor_st16_like(),
				       fixture_fluxes()->moon,
				       fixture_fluxes()->drs, &m);
		assert_int_equal(stray_fdr_threshold(&m, &i_sdt, NULL), 0);
		assert_int_equal(stray_fdr_log_rate(&m, 1.0, i_sdt, &lf, NULL), 0);
		m.f_src_ph_s_m2 *= pow(10.0, -0.4 * dm);
		assert_int_equal(stray_fdr_log_rate(&m, 1.0, i_sdt, &lh, NULL), 0);
		assert_near(full.ln_fdr[FDRFW_MOON], lf, 1e-3 * fabs(lf) + 1e-4);
		assert_near(half.ln_fdr[FDRFW_MOON], lh, 1e-3 * fabs(lh) + 1e-4);
	}
}

/* Looking at the sunlit Earth from LEO: in the field and excluded. */
static void test_sunlit_earth(void **state)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	frame_with_sun_at(&in, 90.0, 0.1f);
	in.pos_km[2] = -6921.0f;	/* 550 km, nadir along +z */
	in.sun_dir[1] = 0.0f;	/* Sun behind the spacecraft: full Earth */
	in.sun_dir[2] = -1.0f;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	assert_true(out.flags & FDRFW_EARTH_IN_FOV);
	assert_true(out.flags & FDRFW_EARTH_EXCLUDED);
	assert_true(out.false_stars[FDRFW_EARTH] > 5.0f);
	assert_near(out.theta_deg[FDRFW_EARTH], 0.0, 1e-6);
}

/* The boresight swinging away from the sunlit Earth, jitter +-0.2 deg:
 * the Earth flag clears once and stays clear; pointing away (zenith) it
 * is never raised. */
static void test_earth_flag_no_chatter(void **state)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;
	uint32_t prev = FDRFW_EARTH_EXCLUDED;
	int i, toggles = 0;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	frame_with_sun_at(&in, 90.0, 0.1f);
	in.pos_km[2] = -6921.0f;	/* 550 km, nadir along +z */
	in.sun_dir[1] = 0.0f;	/* full Earth below */
	in.sun_dir[2] = -1.0f;
	in.moon_dir[0] = 1.0f;
	for (i = 0; i <= 600; i++) {
		/* Boresight tilted from nadir by 0..180 deg about x. */
		double a = (0.3 * i + 0.2 * sin(i * 1.7)) * DEG / 2.0;

		in.q[0] = (float)cos(a);
		in.q[1] = (float)sin(a);
		assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
		if ((out.flags & FDRFW_EARTH_EXCLUDED) != prev)
			toggles++;
		prev = out.flags & FDRFW_EARTH_EXCLUDED;
	}
	assert_int_equal(toggles, 1);
	assert_int_equal(prev, 0);
	assert_near(out.theta_deg[FDRFW_EARTH], 180.0 - 66.9, 1.0);
	assert_true(out.false_stars[FDRFW_EARTH] < 5.0f);
}

/* On-board ephemeris with the lunar parallax of a LEO position. */
static void test_ephemeris_mode_parallax(void **state)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;
	float moon[3], sun[3];
	double topo[3], n = 0.0, th_topo;
	int i;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	memset(&in, 0, sizeof(in));
	in.q[0] = 1.0f;
	in.t_exp_s = 0.1f;
	in.t_tt_s = 820000000;	/* 2025-12-27 */
	fdrfw_moon_pos_km(in.t_tt_s, moon);
	fdrfw_sun_dir(in.t_tt_s, sun);
	/* A position 7000 km off the Earth-Moon line. */
	in.pos_km[0] = 7000.0f * moon[1] / hypotf(moon[0], moon[1]);
	in.pos_km[1] = -7000.0f * moon[0] / hypotf(moon[0], moon[1]);
	for (i = 0; i < 3; i++) {
		topo[i] = (double)moon[i] - (double)in.pos_km[i];
		n += topo[i] * topo[i];
	}
	th_topo = acos(topo[2] / sqrt(n)) / DEG;	/* boresight +z */
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	assert_near(out.theta_deg[FDRFW_MOON], th_topo, 1e-3);
	assert_near(out.theta_deg[FDRFW_SUN], acos((double)sun[2]) / DEG, 1e-3);
	/* The parallax is about 1 deg here: geocentric would be wrong. */
	{
		double g = sqrt((double)moon[0] * moon[0] +
				(double)moon[1] * moon[1] +
				(double)moon[2] * moon[2]), dot = 0.0;

		for (i = 0; i < 3; i++)
			dot += (double)moon[i] / g * topo[i];
		assert_true(acos(dot / sqrt(n)) / DEG > 0.9);
	}
}

static void expect_invalid(struct fdrfw_ctx *ctx, const struct fdrfw_input *in)
{
	struct fdrfw_output out;
	uint32_t latched = ctx->latched;

	assert_int_equal(fdrfw_frame(ctx, in, &out), FDRFW_EINPUT);
	assert_true(out.flags & FDRFW_INPUT_INVALID);
	assert_int_equal(out.flags & FDRFW_EXCLUDED_ALL, FDRFW_EXCLUDED_ALL);
	assert_int_equal(ctx->latched, latched);	/* state untouched */
}

static void test_invalid_inputs_flagged(void **state)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input good, in;
	struct fdrfw_output out;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	frame_with_sun_at(&good, 40.0, 0.1f);
	assert_int_equal(fdrfw_frame(&ctx, &good, &out), FDRFW_OK);
	assert_false(out.flags & FDRFW_INPUT_INVALID);
	in = good; in.q[2] = NAN; expect_invalid(&ctx, &in);
	in = good; in.q[0] = 0.0f; expect_invalid(&ctx, &in);	/* zero q */
	in = good; in.q[0] = 1.1f; expect_invalid(&ctx, &in);	/* unnormalised */
	in = good; in.q[3] = INFINITY; expect_invalid(&ctx, &in);
	in = good; in.sun_dir[0] = NAN; expect_invalid(&ctx, &in);
	in = good; memset(in.sun_dir, 0, sizeof(in.sun_dir));
	expect_invalid(&ctx, &in);				/* zero vector */
	in = good; in.moon_dir[0] = 2.0f; expect_invalid(&ctx, &in);
	in = good; in.pos_km[1] = NAN; expect_invalid(&ctx, &in);
	in = good; in.pos_km[2] = 100.0f; expect_invalid(&ctx, &in);
	in = good; in.t_exp_s = 0.0f; expect_invalid(&ctx, &in);
	in = good; in.t_exp_s = -0.1f; expect_invalid(&ctx, &in);
	in = good; in.t_exp_s = NAN; expect_invalid(&ctx, &in);
	/* Within tolerance, a slightly unnormalised quaternion is fine. */
	in = good; in.q[0] = 1.0005f;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
}

static void test_bad_table_never_used(void **state)
{
	struct fdrfw_table bad = table;
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;

	(void)state;
	bad.log10_alpha[10] += 0.5f;	/* corrupted in memory */
	assert_int_equal(fdrfw_init(&ctx, &bad), FDRFW_ECRC);
	frame_with_sun_at(&in, 40.0, 0.1f);
	expect_invalid(&ctx, &in);
}

/* The Earth term by the full quadrature, as the module sums it (float,
 * node by node), its ln FDR and ln FDR at the envelope by libstray. */
static void earth_by_nodes(const struct fdrfw_ctx *ctx,
			   const struct fdrfw_input *in, int latched,
			   double *ln, double *ln_env)
{
	const struct fdrfw_table *t = ctx->table;
	struct stray_fdr_model m = ctx->model;
	struct fdrfw_earth_cap cap;
	float sun[3], b[3], f_tot = 0.0f, fa = 0.0f, fe = 0.0f;
	unsigned k;

	assert_true(fdrfw_unit(in->sun_dir, sun));
	assert_true(fdrfw_earth_cap(in->pos_km, sun, &cap));
	fdrfw_boresight_renorm(in->q, b);
	for (k = 0; k < FDRFW_EARTH_NODES; k++) {
		struct fdrfw_earth_node nd;
		float f, th;

		fdrfw_earth_node(&cap, k, &nd);
		if (!(nd.cos_sun > 0.0f))
			continue;
		f = t->earth_albedo * t->f_sun_ph_s_m2 * nd.cos_sun *
		    0.318309886183790672f * nd.omega_sr;
		th = fdrfw_angle_deg(b, nd.dir);
		f_tot += f;
		fa += f * fdrfw_alpha_at(t, th);
		fe += f * fdrfw_envelope_at(t, latched ? th - t->hysteresis_deg : th);
	}
	*ln = *ln_env = -HUGE_VAL;
	if (!(f_tot > 0.0f))
		return;
	m.f_src_ph_s_m2 = f_tot;
	assert_int_equal(stray_fdr_log_rate(&m, fa / f_tot, ctx->i_sdt_e, ln,
					    NULL), 0);
	assert_int_equal(stray_fdr_log_rate(&m, fe / f_tot, ctx->i_sdt_e,
					    ln_env, NULL), 0);
}

/* The module skips the Earth's nodes (and a source's own FDR) where a
 * bound is under 1e-30: against the full quadrature, the same Earth flag
 * latched or not, the same ln FDR above 1e-30, below it elsewhere; at LEO,
 * MEO and GEO with the boresight swept from zenith to nadir, so both the
 * shortcut and the full sum are taken. */
static void test_earth_shortcut_exact(void **state)
{
	static const float r_km[] = { 6921.0f, 12000.0f, 42164.0f };
	const double floor_ln = log(1e-30);
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;
	int a, i, lat, skipped = 0, full = 0;

	(void)state;
	assert_int_equal(fdrfw_init(&ctx, &table), FDRFW_OK);
	for (a = 0; a < 3; a++)
		for (lat = 0; lat < 2; lat++)
			for (i = 0; i <= 180; i++) {
				double ln, ln_env, tilt = i * DEG;

				/* zenith +z, the Sun 60 deg from it: the
				 * cap part lit; boresight tilted about x */
				frame_with_sun_at(&in, 0.0, 0.1f);
				in.pos_km[2] = r_km[a];
				in.sun_dir[0] = 0.8660254f;
				in.sun_dir[2] = 0.5f;
				in.moon_dir[0] = -1.0f;
				in.q[0] = (float)cos(tilt / 2.0);
				in.q[1] = (float)sin(tilt / 2.0);
				ctx.latched = lat ? FDRFW_EARTH_EXCLUDED : 0u;
				assert_int_equal(fdrfw_frame(&ctx, &in, &out),
						 FDRFW_OK);
				earth_by_nodes(&ctx, &in, lat, &ln, &ln_env);
				assert_int_equal(
					(out.flags & FDRFW_EARTH_EXCLUDED) != 0,
					ln_env >= ctx.ln_fdr_tolerated);
				if (ln >= floor_ln) {
					assert_true(fabs((double)out.ln_fdr[FDRFW_EARTH] -
						ln) <= 1e-5 * fabs(ln) + 1e-5);
					full++;
				} else {
					assert_true((double)out.ln_fdr[FDRFW_EARTH] <
						    floor_ln + 1e-3);
					skipped += ln > -HUGE_VAL &&
						   isinf(out.ln_fdr[FDRFW_EARTH]);
				}
			}
	assert_true(full > 20);
	assert_true(skipped > 20);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sun_flag_matches_exclusion_angle),
		cmocka_unit_test(test_hysteresis_no_chatter),
		cmocka_unit_test(test_eclipse),
		cmocka_unit_test(test_moon_phase_and_field),
		cmocka_unit_test(test_sunlit_earth),
		cmocka_unit_test(test_earth_flag_no_chatter),
		cmocka_unit_test(test_earth_shortcut_exact),
		cmocka_unit_test(test_ephemeris_mode_parallax),
		cmocka_unit_test(test_invalid_inputs_flagged),
		cmocka_unit_test(test_bad_table_never_used),
	};

	return cmocka_run_group_tests(tests, setup, NULL);
}
