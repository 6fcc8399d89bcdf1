/*
 * test_light_paths.c - strategy B (light-side single scatter, MIS with the
 * detector-side paths; tracer/light.h): B alone and A alone against the
 * configuration-factor closed form of a Lambertian disk lit at grazing
 * incidence, the MIS combination against A on ref4 and a rounded vane
 * baffle, bit-identity for threads and for a split into batch ranges and
 * angle subsets, and the inverse maps B's weights need.
 */
#include <string.h>

#include "tracer/batches.h"
#include "tracer/brdf.h"
#include "tracer/scene_load.h"
#include "tracer_test.h"

/* Configuration factor from disk a to a coaxial parallel disk b at
 * distance h (Siegel and Howell, Thermal Radiation Heat Transfer, app. C). */
static double coaxial_disks_f(double a, double b, double h)
{
	double ra = a / h, rb = b / h;
	double x = 1.0 + (1.0 + rb * rb) / (ra * ra);

	return 0.5 * (x - sqrt(x * x - 4.0 * rb * rb / (ra * ra)));
}

/* u -> concentric disk -> back, and the detector's direction map. */
static void test_light_inverse_maps(void **state)
{
	struct tracer_detector d;
	int i;

	(void)state;
	memset(&d, 0, sizeof(d));
	d.shape = TRACER_DET_DISK;
	d.normal = v3_norm(v3(0.3, -0.2, 1.0));
	d.radius_mm = 1.0;
	for (i = 0; i < 2000; i++) {
		double u1 = (i % 47 + 0.5) / 47.0, u2 = (i / 47 + 0.5) / 43.0;
		double x, y, v1, v2, proj;
		struct vec3 w;

		tracer_sample_disk(u1, u2, &x, &y);
		tracer_sample_disk_inverse(x, y, &v1, &v2);
		assert_near(v1, u1, 1e-12);
		assert_near(v2, u2, 1e-12);
		d.accept_half_angle_deg = i % 2 ? 30.0 : 0.0;
		w = tracer_detector_sample_dir(&d, u1, u2, &proj);
		tracer_detector_dir_inverse(&d, w, &v1, &v2);
		assert_near(v1, u1, 1e-9);
		assert_near(v2, u2, 1e-9);
	}
}

/*
 * A Lambertian disk (radius b, rho) at z = h facing down onto the
 * detector disk (radius a) at z = 0, lit from below the detector's plane
 * at theta > 90 deg, i.e. at 90 - theta from grazing: its irradiance is
 * E cos_d, cos_d = -cos theta, so P/(E A_a) = rho cos_d F_a->b.
 */
static void grazing_disk(struct tracer_scene *s, double theta, double b,
			 double h, double rho)
{
	struct vec3 d = tracer_source_dir(theta);
	int g;

	tracer_scene_init(s);
	g = tracer_mesh_group(&s->mesh, "disk", NULL);
	test_band(&s->mesh, 0.0, h, b, h, 512, g);
	s->material[g].ops = &tracer_brdf_lambert_ops;
	s->material[g].rho = rho;
	test_detector(s, 5.0, v3(0, 0, 0), v3(0, 0, 1));
	/* the beam through the disk's shadow on z = 0 */
	s->beam.center = v3(0, -h * d.y / d.z, 0);
	s->beam.normal = v3(0, 0, -1);
	s->beam.radius_mm = b + 1.0;
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

static void trace_light(const struct tracer_scene *s, const double *th,
			size_t n, uint64_t paths, const double *ratio,
			int weights, int threads, struct tracer_result *r)
{
	struct tracer_trace_opts o;
	struct stray_error err;

	stray_error_clear(&err);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = n;
	o.n_paths = paths;
	o.threads = threads;
	o.n_batches = 32;
	o.seed = 20261202;
	o.light_ratio = ratio;
	o.light_weights = weights;
	o.light_paths = ratio == NULL && weights < 0;
	if (o.light_weights < 0)
		o.light_weights = TRACER_LIGHT_BALANCE;
	assert_int_equal(tracer_trace(s, &o, r, &err), 0);
}

static void test_light_grazing_disk_closed_form(void **state)
{
	const double ths[] = { 90.5, 92.0 }, a = 5, b = 10, h = 10, rho = 0.5;
	const double one[] = { 1.0 };
	size_t k;

	(void)state;
	for (k = 0; k < 2; k++) {
		struct tracer_scene s;
		struct tracer_result ra, rb, rm;
		double want = rho * -cos(ths[k] * M_PI / 180.0) *
			      coaxial_disks_f(a, b, h), pa, sa, pb, sb, pm, sm;

		grazing_disk(&s, ths[k], b, h, rho);
		trace_light(&s, &ths[k], 1, 40000, NULL, 0, 2, &ra);
		trace_light(&s, &ths[k], 1, 40000, one, TRACER_LIGHT_ONLY, 2,
			    &rb);
		trace_light(&s, &ths[k], 1, 40000, one, TRACER_LIGHT_BALANCE,
			    2, &rm);
		tracer_result_power(&ra, 0, 1, &pa, &sa);
		tracer_result_power(&rb, 0, 1, &pb, &sb);
		tracer_result_power(&rm, 0, 1, &pm, &sm);
		assert_near(pa, want, 3.0 * sa + 1e-4 * want);
		assert_near(pb, want, 3.0 * sb + 1e-4 * want);
		assert_near(pm, want, 3.0 * sm + 1e-4 * want);
		assert_true(sb > 0.0 && sm > 0.0);
		tracer_result_free(&ra);
		tracer_result_free(&rb);
		tracer_result_free(&rm);
		tracer_scene_free(&s);
	}
}

static void load(const char *name, const char *const *sets, int n,
		 struct tracer_scene *s)
{
	struct stray_error err;

	stray_error_clear(&err);
	tracer_scene_init(s);
	assert_int_equal(tracer_scene_load(name, sets, n, s, &err), 0);
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

/* alpha of r and q at every angle within 3 combined sigma (order: -1 all,
 * or one order). */
static void assert_agree(const struct tracer_result *r,
			 const struct tracer_result *q, int order)
{
	size_t j;

	for (j = 0; j < r->n_theta; j++) {
		double a, sa, b, sb;

		tracer_result_power(r, j, order, &a, &sa);
		tracer_result_power(q, j, order, &b, &sb);
		if (getenv("TRACER_TEST_VERBOSE"))
			print_message("%g deg: %.5g +- %.2g, %.5g +- %.2g\n",
				      r->theta_deg[j], a, sa, b, sb);
		assert_near(a, b, 3.0 * hypot(sa, sb) + 1e-12);
	}
}

/* The pilot-sized MIS on ref4 equals A; B alone (single scatter) too;
 * and B pays at the grazing angles. */
static void test_light_ref4_mis_equals_a(void **state)
{
	const double th[] = { 0, 60, 80, 88.5, 89, 89.5 };
	const double quarter[] = { 0, 0.25, 0.25, 0.25, 0.25, 0.25 };
	struct tracer_scene s;
	struct tracer_result ra, rm, rb;
	double a, sa, m, sm;

	(void)state;
	load("ref4", NULL, 0, &s);
	trace_light(&s, th, 6, 200000, NULL, 0, 2, &ra);
	trace_light(&s, th, 6, 200000, NULL, -1, 2, &rm);
	trace_light(&s, th, 6, 200000, quarter, TRACER_LIGHT_ONLY, 2, &rb);
	assert_agree(&ra, &rm, -1);
	assert_agree(&ra, &rb, 1);
	tracer_result_power(&ra, 5, -1, &a, &sa);
	tracer_result_power(&rm, 5, -1, &m, &sm);
	assert_true(sm / m < 0.7 * sa / a);	/* 89.5 deg: B was used */
	tracer_result_free(&ra);
	tracer_result_free(&rm);
	tracer_result_free(&rb);
	tracer_scene_free(&s);
}

/* A rounded vane baffle of another reflectance: MIS equals A, and B
 * takes part (the grazing angle's error is not A's). */
static void test_light_vanes_mis_equals_a(void **state)
{
	const char *sets[] = { "edge_radius=0.05", "reflectance=0.2" };
	const double th[] = { 0, 70, 85, 89, 89.5 };
	struct tracer_scene s;
	struct tracer_result ra, rm;
	double a, sa, m, sm;

	(void)state;
	load("ref4", sets, 2, &s);
	trace_light(&s, th, 5, 150000, NULL, 0, 2, &ra);
	trace_light(&s, th, 5, 150000, NULL, -1, 2, &rm);
	assert_agree(&ra, &rm, -1);
	tracer_result_power(&ra, 4, -1, &a, &sa);
	tracer_result_power(&rm, 4, -1, &m, &sm);
	assert_true(sm != sa);
	tracer_result_free(&ra);
	tracer_result_free(&rm);
	tracer_scene_free(&s);
}

static void assert_same(const struct tracer_result *a,
			const struct tracer_result *b)
{
	size_t n = (size_t)a->n_batches * a->n_theta * TRACER_ORDERS;

	assert_int_equal(a->n_theta, b->n_theta);
	assert_memory_equal(a->power, b->power, n * sizeof(double));
	assert_memory_equal(a->energy, b->energy, (size_t)a->n_batches *
			    TRACER_ENERGY_N * sizeof(double));
}

/* Same seed, 1 or 2 threads: the same bits. */
static void test_light_threads_identical(void **state)
{
	const double th[] = { 0, 80, 89, 89.5 };
	struct tracer_scene s;
	struct tracer_result r1, r2;

	(void)state;
	load("ref4", NULL, 0, &s);
	trace_light(&s, th, 4, 30000, NULL, -1, 1, &r1);
	trace_light(&s, th, 4, 30000, NULL, -1, 2, &r2);
	assert_same(&r1, &r2);
	/* one ulp at 89.5 deg is seen: the check can fail */
	r1.power[3 * TRACER_ORDERS + 1] = nextafter(
		r1.power[3 * TRACER_ORDERS + 1], 1.0);
	assert_true(memcmp(r1.power, r2.power, 4 * TRACER_ORDERS *
			   sizeof(double)) != 0);
	tracer_result_free(&r1);
	tracer_result_free(&r2);
	tracer_scene_free(&s);
}

/* Batches [b0, b0 + nb) at angles [j0, j0 + nj) of the pass o. */
static void piece(const struct tracer_scene *s,
		  const struct tracer_trace_opts *o,
		  const struct tracer_guide *g, size_t j0, size_t nj,
		  int b0, int nb, struct tracer_result *r)
{
	struct tracer_trace_opts po = *o;
	struct stray_error err;

	stray_error_clear(&err);
	po.theta_deg = o->theta_deg + j0;
	po.light_ratio = o->light_ratio + j0;
	po.n_theta = nj;
	assert_int_equal(tracer_trace_batches(s, &po, g, b0, nb, NULL, r,
					      &err), 0);
}

/* The pieces of a pass (4 batches x 2 angle subsets) against whole. */
static void assert_pieces(const struct tracer_scene *s,
			  const struct tracer_trace_opts *o,
			  const struct tracer_guide *g,
			  const struct tracer_result *whole)
{
	int b0;

	for (b0 = 0; b0 < 8; b0 += 4) {
		size_t j0, j, b;

		for (j0 = 0; j0 < 5; j0 += 3) {
			size_t nj = j0 ? 2 : 3;
			struct tracer_result p;

			piece(s, o, g, j0, nj, b0, 4, &p);
			for (b = (size_t)b0; b < (size_t)b0 + 4; b++)
				for (j = 0; j < nj; j++)
					assert_memory_equal(
						p.power + (b * nj + j) *
						TRACER_ORDERS,
						whole->power + (b * 5 + j0 + j) *
						TRACER_ORDERS,
						TRACER_ORDERS * sizeof(double));
			tracer_result_free(&p);
		}
	}
}

/* The pieces' trace on ref4: five angles up to grazing, 20 000 paths in
 * 8 batches. */
#define PIECE_N 5
static const double piece_theta[PIECE_N] = { 0, 80, 88.5, 89, 89.5 };

static void piece_trace(struct tracer_scene *s, struct tracer_trace_opts *o)
{
	load("ref4", NULL, 0, s);
	tracer_trace_defaults(o);
	o->theta_deg = piece_theta;
	o->n_theta = PIECE_N;
	o->n_paths = 20000;
	o->n_batches = 8;
}

/* Pieces (batch ranges x angle subsets) give the whole pass's bits, as
 * mpi/ assembles them; B's streams follow the angle, not its index. */
static void test_light_pieces_identical(void **state)
{
	const double ratio[PIECE_N] = { 0, 0.1, 0.2, 0.3, 0.5 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_result whole;
	struct stray_error err;

	(void)state;
	piece_trace(&s, &o);
	o.guide = 0;
	o.light_ratio = ratio;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace_batches(&s, &o, NULL, 0, 8, NULL,
					      &whole, &err), 0);
	assert_pieces(&s, &o, NULL, &whole);
	tracer_result_free(&whole);
	tracer_scene_free(&s);
}

/*
 * What mpi/'s farm would do with light_paths: the pilot with B's
 * statistics (tracer_trace_batches_light), the guide and the ratios from
 * it, the main pass in pieces: bit-identical to tracer_trace().
 */
static void test_light_farm_flow(void **state)
{
	struct tracer_trace_opts o, po;
	struct tracer_scene s;
	struct tracer_result whole, pilot;
	struct tracer_guide g;
	struct stray_error err;
	double ratio[PIECE_N], *s2, *lp;

	(void)state;
	piece_trace(&s, &o);
	o.light_paths = 1;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &whole, &err), 0);
	assert_true(tracer_pilot_wanted(&o));
	tracer_pilot_opts(&o, &po);
	s2 = calloc((size_t)po.n_batches * TRACER_GUIDE_CELLS * PIECE_N,
		    sizeof(double));
	lp = calloc((size_t)po.n_batches * PIECE_N * TRACER_LIGHT_STATS,
		    sizeof(double));
	assert_non_null(s2);
	assert_non_null(lp);
	assert_int_equal(tracer_trace_batches_light(&s, &po, NULL, 0,
		po.n_batches, s2, lp, &pilot, &err), 0);
	assert_int_equal(tracer_guide_from_pilot(&g, &pilot, s2), 0);
	tracer_light_alloc(&pilot, lp, ratio);
	assert_true(ratio[PIECE_N - 1] > 0.0);	/* B at 89.5 deg */
	assert_true(ratio[0] == 0.0);	/* none where nothing scatters */
	o.light_ratio = ratio;
	assert_pieces(&s, &o, &g, &whole);
	tracer_result_free(&pilot);
	tracer_result_free(&whole);
	free(s2);
	free(lp);
	tracer_scene_free(&s);
}

/* A ratio out of range is refused, naming the field. */
static void test_light_bad_ratio(void **state)
{
	const double th[] = { 0, 89.5 }, bad[] = { 0, NAN }, big[] = { 0, 65 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_result r;
	struct stray_error err;

	(void)state;
	load("ref4", NULL, 0, &s);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 2;
	o.light_ratio = bad;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &r, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "light_ratio");
	o.light_ratio = big;
	assert_int_equal(tracer_trace(&s, &o, &r, &err), STRAY_EINVAL);
	tracer_scene_free(&s);
}

/* No B sample anywhere (ratios 0) is the detector-side estimator, bit
 * for bit: the MIS hook leaves A alone. */
static void test_light_off_is_a(void **state)
{
	const double th[] = { 0, 60, 89.5 }, zero[] = { 0, 0, 0 };
	struct tracer_scene s;
	struct tracer_result r1, r2;

	(void)state;
	load("ref4", NULL, 0, &s);
	trace_light(&s, th, 3, 20000, NULL, 0, 2, &r1);
	trace_light(&s, th, 3, 20000, zero, TRACER_LIGHT_BALANCE, 2, &r2);
	assert_same(&r1, &r2);
	tracer_result_free(&r1);
	tracer_result_free(&r2);
	tracer_scene_free(&s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_light_inverse_maps),
		cmocka_unit_test(test_light_grazing_disk_closed_form),
		cmocka_unit_test(test_light_ref4_mis_equals_a),
		cmocka_unit_test(test_light_vanes_mis_equals_a),
		cmocka_unit_test(test_light_threads_identical),
		cmocka_unit_test(test_light_pieces_identical),
		cmocka_unit_test(test_light_farm_flow),
		cmocka_unit_test(test_light_off_is_a),
		cmocka_unit_test(test_light_bad_ratio),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
