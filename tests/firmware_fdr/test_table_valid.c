/*
 * test_table_valid.c - a valid CRC is not a valid table (issue 14): every
 * scalar of the flight table just outside its physical domain, resealed,
 * is refused by fdrfw_table_check and fdrfw_init with that field's code;
 * fields inside their domains but inconsistent with the table's own model
 * (I_sdt of eq. 2.16, the Sun's alpha_req of fig. 2.7, its exclusion angle
 * of fig. 5.1) are refused at init; the ground builder refuses what the
 * module would, naming the field; and the Sun on the boresight is flagged
 * by a valid table.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fdrfw/fdrfw.h"
#include "fdrfw/table_build.h"
#include "fixture.h"
#include "stray/sensor.h"

/* The one field list, expanded here as the module expands it. */
static const struct {
	const char *name;
	float lo, hi;
} scalars[] = {
#define T_M(tf, mf, lo, hi) { #tf, lo, hi },
#define T_S(tf, lo, hi) { #tf, lo, hi },
	FDRFW_MODEL_FIELDS(T_M)
	FDRFW_TABLE_SCALARS(T_S)
};

#define N_SCALARS (sizeof(scalars) / sizeof(scalars[0]))

/* Scalar i of a table (the words after n_curve, in the lists' order). */
static float *scalar(struct fdrfw_table *t, size_t i)
{
	return &t->t_exp_nominal_s + i;
}

/* Both the table check and init refuse t, resealed, with rc. */
static void expect_refused(struct fdrfw_table *t, int rc, int at_init_only)
{
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;

	fdrfw_table_seal(t);
	assert_int_equal(fdrfw_table_check(t), at_init_only ? FDRFW_OK : rc);
	assert_int_equal(fdrfw_init(&ctx, t), rc);
	/* A refused table is never used: every frame is invalid. */
	memset(&in, 0, sizeof(in));
	in.q[0] = 1.0f;
	in.t_exp_s = 0.1f;
	in.pos_km[2] = 7000.0f;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_EINPUT);
	assert_true(out.flags & FDRFW_INPUT_INVALID);
}

static void test_lists_cover_every_scalar(void **state)
{
	(void)state;
	assert_int_equal(N_SCALARS, FDRFW_SCALARS);
	assert_int_equal(offsetof(struct fdrfw_table, det_du),
			 offsetof(struct fdrfw_table, t_exp_nominal_s) +
			 4u * (N_SCALARS - 1u));
	assert_string_equal(fdrfw_field_name(FDRFW_FIELD_OF(
		FDRFW_EFIELD_OF(a_px_m2))), "a_px_m2");
	assert_string_equal(fdrfw_field_name(FDRFW_FIELD_OF(
		FDRFW_EFIELD_OF(log10_alpha))), "log10_alpha");
	assert_int_equal(FDRFW_FIELD_OF(FDRFW_ECRC), -1);
	assert_null(fdrfw_field_name(FDRFW_FIELD_OF(FDRFW_ECRC)));
}

/* Every scalar at min-, max+ (the next float out), NaN and +-inf: that
 * field's code; at min and max exactly, not that field's range. */
static void test_every_scalar_bounded(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < N_SCALARS; i++) {
		const float bad[] = { nextafterf(scalars[i].lo, -INFINITY),
				      nextafterf(scalars[i].hi, INFINITY),
				      NAN, INFINITY, -INFINITY };
		size_t k;

		for (k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
			struct fdrfw_table t;

			fixture_table(&t);
			assert_true(*scalar(&t, i) >= scalars[i].lo &&
				    *scalar(&t, i) <= scalars[i].hi);
			*scalar(&t, i) = bad[k];
			print_message("%s = %.9g\n", scalars[i].name,
				      (double)bad[k]);
			expect_refused(&t, FDRFW_EFIELD_WORD(FDRFW_SCALAR_WORD + i),
				       0);
		}
	}
}

/* The reproducers of issue 14: i_sdt_e -1, 0, 1e30 and a_px 1e-38, each
 * resealed with a valid CRC, passed fdrfw_init before. */
static void test_issue_reproducers_refused(void **state)
{
	const float i_sdt[] = { -1.0f, 0.0f, 1e30f };
	struct fdrfw_table t;
	size_t k;

	(void)state;
	for (k = 0; k < 3; k++) {
		fixture_table(&t);
		t.i_sdt_e = i_sdt[k];
		expect_refused(&t, FDRFW_EFIELD_OF(i_sdt_e), 0);
	}
	fixture_table(&t);
	t.a_px_m2 = 1e-38f;
	expect_refused(&t, FDRFW_EFIELD_OF(a_px_m2), 0);
}

/* In its domain but not what the table's own model gives: refused at
 * init (I_sdt, alpha_req) or by the check (the exclusion envelope). */
static void test_inconsistent_fields_refused(void **state)
{
	struct fdrfw_table t;

	(void)state;
	fixture_table(&t);
	t.i_sdt_e *= 10.0f;		/* eq. 2.16 gives a tenth of it */
	expect_refused(&t, FDRFW_EFIELD_OF(i_sdt_e), 1);
	fixture_table(&t);
	t.i_sdt_e *= 1.01f;
	expect_refused(&t, FDRFW_EFIELD_OF(i_sdt_e), 1);

	fixture_table(&t);
	t.alpha_req_sun *= 10.0f;	/* the FDR there is not the rate */
	expect_refused(&t, FDRFW_EFIELD_OF(alpha_req_sun), 1);

	/* An exclusion angle short of where the envelope falls to
	 * alpha_req: 0.001 deg with a real curve, or 5 deg early. */
	fixture_table(&t);
	t.exclusion_sun_deg = 1e-3f;
	expect_refused(&t, FDRFW_EFIELD_OF(exclusion_sun_deg), 0);
	fixture_table(&t);
	t.exclusion_sun_deg -= 5.0f;
	expect_refused(&t, FDRFW_EFIELD_OF(exclusion_sun_deg), 0);
	fixture_table(&t);
	t.alpha_req_sun *= 0.1f;	/* the claimed angle is then early */
	expect_refused(&t, FDRFW_EFIELD_OF(exclusion_sun_deg), 0);

	fixture_table(&t);
	t.n_tot = 100.0f;
	t.n_pps = 101.0f;
	expect_refused(&t, FDRFW_EFIELD_OF(n_pps), 0);
	fixture_table(&t);
	t.k_px = 2.0f;
	expect_refused(&t, FDRFW_EFIELD_OF(k_px), 0);
}

/* Replace the curve by one of constant log10 alpha (its envelope too). */
static void flat_curve(struct fdrfw_table *t, float l)
{
	uint32_t i;

	for (i = 0; i < t->n_curve; i++)
		t->log10_alpha[i] = t->log10_alpha_tail[i] = l;
}

/* An all-zero curve, or one everywhere below the Sun's alpha_req, would
 * never flag the Sun: refused, whatever exclusion angle it claims. */
static void test_blind_curves_refused(void **state)
{
	struct fdrfw_table t;

	(void)state;
	fixture_table(&t);
	flat_curve(&t, FDRFW_LOG10_ALPHA_FLOOR);
	expect_refused(&t, FDRFW_EFIELD_OF(log10_alpha), 0);

	fixture_table(&t);
	flat_curve(&t, log10f(t.alpha_req_sun) - 1.0f);
	t.exclusion_sun_deg = 1e-3f;
	expect_refused(&t, FDRFW_EFIELD_OF(exclusion_sun_deg), 0);

	fixture_table(&t);
	t.log10_alpha[3] = -41.0f;	/* below the floor: not a stored alpha */
	expect_refused(&t, FDRFW_EFIELD_OF(log10_alpha), 0);
	fixture_table(&t);
	t.theta_deg[0] = -1.0f;
	expect_refused(&t, FDRFW_EFIELD_OF(theta_deg), 0);
	fixture_table(&t);
	t.theta_deg[t.n_curve - 1] = 180.5f;
	expect_refused(&t, FDRFW_EFIELD_OF(theta_deg), 0);
	fixture_table(&t);
	t.log10_alpha_tail[0] += 1.0f;
	expect_refused(&t, FDRFW_EFIELD_OF(log10_alpha_tail), 0);
	fixture_table(&t);
	t.n_curve = 1;
	expect_refused(&t, FDRFW_EFIELD_OF(n_curve), 0);
}

/* A valid table flags the Sun on the boresight (and in the field). */
static void test_sun_on_boresight_flagged(void **state)
{
	struct fdrfw_table t;
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;

	(void)state;
	fixture_table(&t);
	assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
	memset(&in, 0, sizeof(in));
	in.q[0] = 1.0f;			/* boresight +z */
	in.t_exp_s = t.t_exp_nominal_s;
	in.pos_km[2] = 7000.0f;		/* the Earth behind, no eclipse */
	in.use_given_dirs = 1;
	in.sun_dir[2] = 1.0f;
	in.moon_dir[0] = 1.0f;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	assert_true(out.flags & FDRFW_SUN_EXCLUDED);
	assert_true(out.flags & FDRFW_SUN_IN_FOV);
	assert_true(out.false_stars[FDRFW_SUN] > t.fdr_tolerated);
	/* And at a short exposure, threshold recomputed on board. */
	in.t_exp_s = 0.01f;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	assert_true(out.flags & FDRFW_SUN_EXCLUDED);
}

/* The ground refuses what the module would, naming the field. */
static void test_ground_names_field(void **state)
{
	const struct stray_curve_view *c = fixture_curve();
	double zeros[128] = { 0 };
	struct stray_curve_view z = *c;
	struct fdrfw_build_params p = {
		.hysteresis_deg = FDRFW_BUILD_HYSTERESIS_DEG,
		.earth_albedo = FDRFW_BUILD_ALBEDO,
	};
	struct fdrfw_table t;
	struct stray_error err;

	(void)state;
	p.f_sun_ph_s_m2 = fixture_fluxes()->sun;
	p.f_moon_full_ph_s_m2 = fixture_fluxes()->moon;
	p.f_drs_ph_s_m2 = fixture_fluxes()->drs;

	/* An all-zero curve: Sun exclusion 0 deg, refused. */
	z.alpha = zeros;
	stray_error_clear(&err);
	assert_int_not_equal(fdrfw_table_build(&z, stray_sensor_st16_like(),
					       &p, &t, &err), 0);
	assert_non_null(err.field);
	assert_string_equal(err.field, "exclusion_sun_deg");
	assert_true(err.has_value);
	assert_true(err.value == 0.0);

	/* A full Moon ten thousand times its brightness (2e15). */
	p.f_moon_full_ph_s_m2 *= 1e4;
	stray_error_clear(&err);
	assert_int_not_equal(fdrfw_table_build(c, stray_sensor_st16_like(),
					       &p, &t, &err), 0);
	assert_string_equal(err.field, "f_moon_full_ph_s_m2");
	assert_true(err.has_value);
	assert_true(err.value > 1e18);
	/* The same inputs in the domain build. */
	p.f_moon_full_ph_s_m2 = fixture_fluxes()->moon;
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_build(c, stray_sensor_st16_like(), &p,
					   &t, &err), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_lists_cover_every_scalar),
		cmocka_unit_test(test_every_scalar_bounded),
		cmocka_unit_test(test_issue_reproducers_refused),
		cmocka_unit_test(test_inconsistent_fields_refused),
		cmocka_unit_test(test_blind_curves_refused),
		cmocka_unit_test(test_sun_on_boresight_flagged),
		cmocka_unit_test(test_ground_names_field),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
