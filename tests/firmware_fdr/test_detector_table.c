/*
 * test_detector_table.c - the named detector carried by the flight table
 * (issue 28 item 4, table version 3): for each validated detector the
 * module's answer (its false stars, the DRS's detection probability and
 * the exclusion flag) equals libstray's ground model at the table's grid
 * nodes and lies between the nodes' answers in between; the Sun's flag
 * turns at the ground's exclusion angle; a table built for one detector
 * and read for another is refused, as is an older table, a broken grid,
 * a wrong z_drs, and another exposure than the grid's.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "../../firmware_fdr/source_fdr.h"
#include "fdrfw/fdrfw.h"
#include "fdrfw/table_build.h"
#include "fixture.h"
#include "stray/detector.h"
#include "stray/sensor.h"

struct det_case {
	enum stray_detector_kind kind;
	double sigma;
	enum stray_failure_mode binding;	/* issue 28's closing table */
};

static const struct det_case cases[] = {
	{ STRAY_DET_WINDOW, 0.0, STRAY_FAIL_LOST_STARS },
	{ STRAY_DET_THRESHOLD, 0.0, STRAY_FAIL_LOST_STARS },	/* the component model */
	{ STRAY_DET_TETRA3, 3.0, STRAY_FAIL_LOST_STARS },
	{ STRAY_DET_TETRA3, 5.0, STRAY_FAIL_LOST_STARS },
};
#define N_CASES (sizeof(cases) / sizeof(cases[0]))

static void params_for(const struct det_case *c, struct fdrfw_build_params *p)
{
	const struct stray_fluxes *fl = fixture_fluxes();

	memset(p, 0, sizeof(*p));
	p->f_sun_ph_s_m2 = fl->sun;
	p->f_moon_full_ph_s_m2 = fl->moon;
	p->f_drs_ph_s_m2 = fl->drs;
	p->hysteresis_deg = FDRFW_BUILD_HYSTERESIS_DEG;
	p->earth_albedo = FDRFW_BUILD_ALBEDO;
	p->detector = c->kind;
	p->detector_sigma = c->sigma;
}

static void build(const struct det_case *c, struct fdrfw_table *t)
{
	struct fdrfw_build_params p;
	struct stray_error err;

	params_for(c, &p);
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_build(fixture_curve(),
			 stray_sensor_st16_like(), &p, t, &err), 0);
}

/* The ground's detector and model, as the builder sets them up. */
static void ground(const struct det_case *c, struct stray_detector *d,
		   struct stray_fdr_model *g)
{
	const struct stray_sensor *s = stray_sensor_st16_like();
	struct fdrfw_build_params p;
	struct stray_fdr_model m;
	struct stray_error err;

	params_for(c, &p);
	stray_sensor_fdr_model(s, p.f_sun_ph_s_m2, p.f_drs_ph_s_m2, &m);
	m.k_px = stray_sensor_k_px(s, STRAY_NORM_CONSISTENT);
	stray_error_clear(&err);
	assert_int_equal(fdrfw_det_setup(s, &p, &m, d, g, &err), 0);
}

/* The ground model at alpha of the Sun's light. */
static void model_at(const struct stray_detector *d,
		     const struct stray_fdr_model *g, double alpha,
		     double *ln_false, double *p)
{
	assert_int_equal(stray_detector_log_false_rate(d, g, alpha, ln_false,
						       NULL), 0);
	assert_int_equal(stray_detector_star_prob(d, g, alpha,
			 stray_fdr_drs_photons(g), p, NULL), 0);
	*ln_false = fmax(*ln_false, (double)FDRFW_DET_LN_FLOOR);
}

/* The module's answer for the Sun's light at alpha (its own envelope). */
static void module_at(struct fdrfw_ctx *ctx, double alpha,
		      struct fdrfw_source_result *r)
{
	fdrfw_grid_source(ctx, (stray_real)ctx->table->f_sun_ph_s_m2,
			  (float)alpha, (float)alpha, r);
}

static double ln_or_floor(double l)
{
	return l > (double)FDRFW_DET_LN_FLOOR ? l : (double)FDRFW_DET_LN_FLOOR;
}

/* At every node the module gives the ground model's numbers (float
 * rounding of the node's place), as their conservative envelope: the
 * most false stars and the lowest P_drs of that background or any darker
 * one (the models saturate and turn at backgrounds far past every
 * requirement: regions merge, tetra3's k sigma rises with the light; the
 * exclusion rule needs answers monotone in the light).  Between nodes
 * the module lies between the nodes' answers. */
static void test_module_equals_ground_at_nodes(void **state)
{
	static struct fdrfw_table t;
	size_t k;

	(void)state;
	for (k = 0; k < N_CASES; k++) {
		const struct det_case *c = &cases[k];
		struct stray_detector d;
		struct stray_fdr_model g;
		struct fdrfw_ctx ctx;
		double f = fixture_fluxes()->sun, worst_mid = 0.0;
		double env_lf = -HUGE_VAL, env_p = HUGE_VAL;
		int i, turned = 0;

		build(c, &t);
		ground(c, &d, &g);
		assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
		assert_int_equal(t.version, 3);
		assert_int_equal(t.detector, (uint32_t)c->kind);
		assert_int_equal(t.n_det, FDRFW_DET_MAX);
		assert_int_equal(fdrfw_table_binding(&t), c->binding);
		for (i = 0; i < FDRFW_DET_MAX; i++) {
			struct fdrfw_source_result r;
			double a = fdrfw_det_node_alpha(&t, f, i), lf, p;

			model_at(&d, &g, a, &lf, &p);
			turned += lf < env_lf || p > env_p;
			env_lf = fmax(env_lf, lf);
			env_p = fmin(env_p, p);
			if (i == FDRFW_DET_BELOW)	/* the Sun's binding node */
				assert_true(lf == env_lf || p == env_p);
			lf = env_lf;
			p = env_p;
			module_at(&ctx, a, &r);
			assert_near(ln_or_floor((double)r.ln_fdr), lf,
				    2e-3 + 1e-4 * fabs(lf));
			assert_near((double)r.p_drs, p, 2e-4);
			/* the flag is the model's verdict, off the edge */
			if (i != FDRFW_DET_BELOW)
				assert_int_equal(r.excluded,
					lf >= log((double)t.fdr_tolerated) ||
					p < (double)t.pr_drs);
		}
		for (i = 0; i + 1 < FDRFW_DET_MAX; i++) {
			struct fdrfw_source_result r, lo, hi;
			double a0 = fdrfw_det_node_alpha(&t, f, i);
			double a1 = fdrfw_det_node_alpha(&t, f, i + 1);
			double am = sqrt(a0 * a1), lf, p;

			module_at(&ctx, a0, &lo);
			module_at(&ctx, a1, &hi);
			module_at(&ctx, am, &r);
			assert_true(ln_or_floor((double)r.ln_fdr) >=
				    ln_or_floor((double)lo.ln_fdr) - 1e-4 &&
				    ln_or_floor((double)r.ln_fdr) <=
				    ln_or_floor((double)hi.ln_fdr) + 1e-4);
			assert_true(r.p_drs <= lo.p_drs + 1e-6 &&
				    r.p_drs >= hi.p_drs - 1e-6);
			assert_true(r.excluded >= lo.excluded &&
				    r.excluded <= hi.excluded);
			model_at(&d, &g, am, &lf, &p);
			worst_mid = fmax(worst_mid, fabs((double)r.p_drs - p));
		}
		print_message("%s k %g: worst |P_drs| between nodes %.3g; "
			      "%d nodes on the envelope, not the model\n",
			      stray_detector_name(c->kind), c->sigma,
			      worst_mid, turned);
	}
}

/* The Sun's flag turns at the ground's alpha_req and exclusion angle
 * (`stray exclusion --detector D`), and the boresight is flagged. */
static void test_sun_flag_at_ground_angle(void **state)
{
	static struct fdrfw_table t;
	size_t k;

	(void)state;
	for (k = 0; k < N_CASES; k++) {
		struct stray_detector d;
		struct stray_fdr_model g;
		struct stray_detector_req req;
		struct fdrfw_source_result r;
		struct fdrfw_ctx ctx;
		stray_real f;

		build(&cases[k], &t);
		ground(&cases[k], &d, &g);
		assert_int_equal(stray_detector_alpha_required(&d, &g,
			(double)t.fdr_tolerated, g.pr_drs, &req, NULL), 0);
		assert_near((double)t.alpha_req_sun, req.alpha_req,
			    1e-6 * req.alpha_req);
		assert_int_equal(req.binding, cases[k].binding);
		assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
		f = (stray_real)t.f_sun_ph_s_m2;
		module_at(&ctx, req.alpha_req * 0.99, &r);
		assert_false(r.excluded);
		module_at(&ctx, req.alpha_req * 1.01, &r);
		assert_true(r.excluded);
		assert_int_equal(fdrfw_point_source(&ctx, f,
			t.exclusion_sun_deg - 0.3f, 0, &r), 0);
		assert_true(r.excluded);
		assert_int_equal(fdrfw_point_source(&ctx, f,
			t.exclusion_sun_deg + 0.3f, 0, &r), 0);
		assert_false(r.excluded);
		assert_int_equal(fdrfw_point_source(&ctx, f, 0.0f, 0, &r), 0);
		assert_true(r.excluded);
	}
}

/* A table read for another detector than it was built for is refused,
 * naming the field and the table's detector. */
static void test_other_detector_refused(void **state)
{
	static struct fdrfw_table t;
	struct stray_error err;

	(void)state;
	build(&cases[0], &t);	/* window */
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_WINDOW, 3.0,
						    "w.bin", &err), 0);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_TETRA3, 3.0,
						    "w.bin", &err),
			 STRAY_EINVAL);
	assert_string_equal(err.field, "detector");
	assert_string_equal(err.text, "window");
	assert_string_equal(err.file, "w.bin");
	assert_non_null(strstr(err.reason, "tetra3"));
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_THESIS, 3.0,
						    "w.bin", &err),
			 STRAY_EINVAL);
	build(&cases[2], &t);	/* tetra3, k = 3 */
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_TETRA3, 3.0,
						    "t.bin", &err), 0);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_TETRA3, 5.0,
						    "t.bin", &err),
			 STRAY_EINVAL);
	assert_non_null(strstr(err.text, "k = 3"));
	fixture_table(&t);	/* thesis */
	stray_error_clear(&err);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_THESIS, 3.0,
						    "x.bin", &err), 0);
	assert_int_equal(fdrfw_table_detector_check(&t, STRAY_DET_WINDOW, 3.0,
						    "x.bin", &err),
			 STRAY_EINVAL);
	assert_string_equal(err.text, "thesis");
}

/* An older table (version 2, before the grid) is refused by the parser
 * and the check; a grid that falls or leaves its domain, an unknown
 * detector, a wrong z_drs (resealed) are refused naming the field. */
static void test_broken_tables_refused(void **state)
{
	static struct fdrfw_table t, u;
	static uint8_t blob[FDRFW_BLOB_SIZE];
	struct fdrfw_ctx ctx;

	(void)state;
	build(&cases[0], &t);
	fdrfw_table_serialize(&t, blob);
	blob[4] = 2;
	assert_int_equal(fdrfw_table_parse(blob, sizeof(blob), &u),
			 FDRFW_EMAGIC);
	assert_int_equal(fdrfw_table_parse(blob, 1624, &u), FDRFW_EMAGIC);
	u = t;
	u.version = 2;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EMAGIC);
	assert_int_equal(fdrfw_init(&ctx, &u), FDRFW_EMAGIC);

	u = t;
	u.det_ln_false[50] = u.det_ln_false[49] - 1.0f;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EFIELD_OF(det_ln_false));
	u = t;
	u.det_p_drs[0] = 1.5f;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EFIELD_OF(det_p_drs));
	u = t;
	u.det_p_drs[60] = u.det_p_drs[59] + 0.1f;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EFIELD_OF(det_p_drs));
	u = t;
	u.detector = 7;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EFIELD_OF(detector));
	u = t;
	u.n_det = 0;	/* a window table without its grid */
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EFIELD_OF(n_det));
	u = t;
	u.det_du = 0.0f;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_EFIELD_OF(det_du));
	u = t;
	u.z_drs = -u.z_drs;	/* Q(-z) = 1 - Pr_drs */
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_table_check(&u), FDRFW_OK);
	assert_int_equal(fdrfw_init(&ctx, &u), FDRFW_EFIELD_OF(z_drs));
	assert_string_equal(fdrfw_field_name(FDRFW_FIELD_OF(
		FDRFW_EFIELD_OF(z_drs))), "z_drs");
	assert_string_equal(fdrfw_field_name(FDRFW_FIELD_OF(
		FDRFW_EFIELD_OF(det_p_drs))), "det_p_drs");
	/* the grid shifted a decade: the Sun's flag no longer turns at
	 * alpha_req_sun */
	u = t;
	u.det_u0 += 2.3f;
	fdrfw_table_seal(&u);
	assert_int_equal(fdrfw_init(&ctx, &u), FDRFW_EFIELD_OF(alpha_req_sun));
}

/* The grid is for the table's exposure: another one is an invalid frame
 * (all flags set), where the thesis's closed form still follows it. */
static void test_grid_exposure_only(void **state)
{
	static struct fdrfw_table t;
	struct fdrfw_ctx ctx;
	struct fdrfw_input in;
	struct fdrfw_output out;

	(void)state;
	build(&cases[2], &t);
	assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
	assert_int_equal(fdrfw_set_exposure(&ctx, t.t_exp_nominal_s),
			 FDRFW_OK);
	assert_int_equal(fdrfw_set_exposure(&ctx, 2.0f * t.t_exp_nominal_s),
			 FDRFW_EINPUT);
	memset(&in, 0, sizeof(in));
	in.q[0] = 1.0f;
	in.pos_km[2] = 7000.0f;
	in.t_tt_s = 86400 * 400;
	in.t_exp_s = 2.0f * t.t_exp_nominal_s;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_EINPUT);
	assert_true(out.flags & FDRFW_INPUT_INVALID);
	in.t_exp_s = t.t_exp_nominal_s;
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	/* each body's P_drs is a probability for a detector table */
	assert_true(out.p_drs[FDRFW_SUN] >= 0.0f &&
		    out.p_drs[FDRFW_SUN] <= 1.0f);
	fixture_table(&t);
	assert_int_equal(fdrfw_init(&ctx, &t), FDRFW_OK);
	assert_int_equal(fdrfw_set_exposure(&ctx, 2.0f * t.t_exp_nominal_s),
			 FDRFW_OK);
	assert_int_equal(fdrfw_frame(&ctx, &in, &out), FDRFW_OK);
	assert_true(isnan(out.p_drs[FDRFW_SUN]));	/* thesis: no model */
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_module_equals_ground_at_nodes),
		cmocka_unit_test(test_sun_flag_at_ground_angle),
		cmocka_unit_test(test_other_detector_refused),
		cmocka_unit_test(test_broken_tables_refused),
		cmocka_unit_test(test_grid_exposure_only),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
