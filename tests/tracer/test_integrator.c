/*
 * test_integrator.c - the estimator against closed forms: direct
 * transmission through an aperture (overlap of two disks), one Lambertian
 * bounce between coaxial disks (configuration factor), the integrating-
 * sphere multiplier rho / (1 - rho), energy bookkeeping, the lens, and
 * bit-identical results for any thread count.
 */
#include <stdlib.h>
#include <string.h>

#include "tracer_test.h"

/* An absorbing plate z = 0 with a hole of radius a over a detector of
 * radius b at z = -h. */
static void aperture_scene(struct tracer_scene *s, double a, double b,
			   double h)
{
	int g;

	tracer_scene_init(s);
	g = tracer_mesh_group(&s->mesh, "plate", NULL);
	test_band(&s->mesh, a, 0.0, 40.0, 0.0, 1024, g);
	s->material[g].ops = NULL;	/* absorber */
	test_detector(s, b, v3(0, 0, -h), v3(0, 0, 1));
	s->beam.center = v3(0, 0, 0);
	s->beam.normal = v3(0, 0, 1);
	s->beam.radius_mm = 40.0;
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

/* Direct light: P/(E A_det) = cos(theta) overlap(a, b, h tan theta) / A_det
 * (the aperture's shadow slides by h tan theta over the detector). */
static void test_integrator_direct_aperture_overlap(void **state)
{
	const double th[] = { 0, 10, 20, 30, 40 }, a = 5, b = 3, h = 10;
	struct tracer_scene s;
	struct tracer_result r;
	size_t j;

	(void)state;
	aperture_scene(&s, a, b, h);
	test_trace(&s, th, 5, 20000, 2, &r);
	for (j = 0; j < 5; j++) {
		double t = th[j] * M_PI / 180.0, p, sg;
		double want = cos(t) * disk_overlap(a, b, h * tan(t)) /
			      (M_PI * b * b);

		tracer_result_power(&r, j, 0, &p, &sg);
		assert_near(p, want, 4.0 * sg + 2e-4 * want + 1e-12);
		assert_true(sg <= 0.01 * want + 1e-12);
		tracer_result_power(&r, j, 1, &p, &sg);
		assert_true(p == 0.0);	/* an absorber scatters nothing */
	}
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* Configuration factor from disk a to a coaxial parallel disk b at
 * distance h (Siegel and Howell, Thermal Radiation Heat Transfer, app. C). */
static double coaxial_disks_f(double a, double b, double h)
{
	double ra = a / h, rb = b / h;
	double x = 1.0 + (1.0 + rb * rb) / (ra * ra);

	return 0.5 * (x - sqrt(x * x - 4.0 * rb * rb / (ra * ra)));
}

/*
 * A Lambertian disk (radius b, reflectance rho) facing the detector from
 * z = h, lit from behind the detector (theta = 180 deg): one bounce gives
 * P = rho E A_b F_b->a, so P/(E A_a) = rho F_a->b (reciprocity).
 */
static void test_integrator_disk_view_factor(void **state)
{
	const double th[] = { 180.0 }, a = 5, b = 10, h = 10, rho = 0.5;
	struct tracer_scene s;
	struct tracer_result r;
	double p, sg, want = rho * coaxial_disks_f(a, b, h);
	int g;

	(void)state;
	tracer_scene_init(&s);
	g = tracer_mesh_group(&s.mesh, "disk", NULL);
	test_band(&s.mesh, 0.0, h, b, h, 512, g);
	s.material[g].ops = &tracer_brdf_lambert_ops;
	s.material[g].rho = rho;
	test_detector(&s, a, v3(0, 0, 0), v3(0, 0, 1));
	s.beam.center = v3(0, 0, 0);
	s.beam.normal = v3(0, 0, -1);	/* lit from below */
	s.beam.radius_mm = 20.0;
	assert_int_equal(tracer_scene_commit(&s, NULL), 0);
	test_trace(&s, th, 1, 100000, 2, &r);
	tracer_result_power(&r, 0, 1, &p, &sg);
	assert_near(p, want, 4.0 * sg + 1e-3 * want);
	assert_true(sg < 0.01 * want);
	tracer_result_power(&r, 0, 0, &p, &sg);
	assert_true(p == 0.0);	/* the detector faces away from the beam */
	tracer_result_power(&r, 0, 2, &p, &sg);
	assert_true(p == 0.0);	/* nothing to bounce to a second time */
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* A UV sphere of radius R with a port (cap above polar angle beta). */
static void sphere_scene(struct tracer_scene *s, double R, double beta,
			 double rho)
{
	const int n_lat = 96, n_phi = 192;
	int g, i;

	tracer_scene_init(s);
	g = tracer_mesh_group(&s->mesh, "wall", NULL);
	for (i = 0; i < n_lat; i++) {
		double t0 = beta + (M_PI - beta) * i / n_lat;
		double t1 = beta + (M_PI - beta) * (i + 1) / n_lat;

		test_band(&s->mesh, R * sin(t0), R * cos(t0),
			  i + 1 == n_lat ? 0.0 : R * sin(t1), R * cos(t1),
			  n_phi, g);
	}
	s->material[g].ops = &tracer_brdf_lambert_ops;
	s->material[g].rho = rho;
	/* a small detector just inside the equator, looking inward */
	test_detector(s, 2.0, v3(R - 0.1, 0, 0), v3(-1, 0, 0));
	s->beam.center = v3(0, 0, R * cos(beta));
	s->beam.normal = v3(0, 0, 1);
	s->beam.radius_mm = R * sin(beta);
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

/*
 * Integrating sphere: every diffuse bounce spreads uniformly over the
 * wall, so the wall irradiance is Phi rho / (A_s (1 - rho (1 - f))), f the
 * port's share of the sphere; with no port loss the multiplier is
 * rho / (1 - rho).  Adjointly, the detector's emission escapes through
 * the port with probability f / (1 - rho (1 - f)).
 */
static void test_integrator_sphere_multiplier(void **state)
{
	const double th[] = { 0.0 }, R = 50, beta = 0.4, rho = 0.5;
	double f = (1.0 - cos(beta)) / 2.0, p, sg, esc = 0, esc2 = 0;
	double want = M_PI * pow(R * sin(beta), 2) * rho /
		      (4.0 * M_PI * R * R * (1.0 - rho * (1.0 - f)));
	double want_esc = f / (1.0 - rho * (1.0 - f));
	struct tracer_scene s;
	struct tracer_result r;
	int b;

	(void)state;
	sphere_scene(&s, R, beta, rho);
	test_trace(&s, th, 1, 100000, 2, &r);
	tracer_result_power(&r, 0, -1, &p, &sg);
	assert_near(p, want, 4.0 * sg + 0.01 * want);
	assert_true(sg < 0.015 * want);
	for (b = 0; b < r.n_batches; b++) {
		double e = r.energy[b * TRACER_ENERGY_N + TRACER_ESCAPED] /
			   r.batch_paths[b];

		esc += e;
		esc2 += e * e;
	}
	esc /= r.n_batches;
	sg = sqrt((esc2 / r.n_batches - esc * esc) / (r.n_batches - 1));
	assert_near(esc, want_esc, 4.0 * sg + 0.01 * want_esc);
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* Emitted = absorbed + escaped + lost, batch by batch within MC error. */
static void test_integrator_energy_bookkeeping(void **state)
{
	const double th[] = { 0.0 };
	struct tracer_scene s;
	struct tracer_result r;
	double m = 0, m2 = 0, sg, esc = 0;
	int b, k;

	(void)state;
	sphere_scene(&s, 50, 0.4, 0.9);	/* many bounces */
	test_trace(&s, th, 1, 20000, 2, &r);
	for (b = 0; b < r.n_batches; b++) {
		double sum = 0.0;

		for (k = 0; k < TRACER_ENERGY_N; k++)
			sum += r.energy[b * TRACER_ENERGY_N + k];
		sum /= r.batch_paths[b];
		m += sum;
		m2 += sum * sum;
		esc += r.energy[b * TRACER_ENERGY_N + TRACER_ESCAPED];
	}
	m /= r.n_batches;
	sg = sqrt((m2 / r.n_batches - m * m) / (r.n_batches - 1));
	assert_near(m, 1.0, 4.0 * sg + 1e-9);
	assert_true(esc > 0.0);
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* One seed, 1, 2 or 3 threads: the same bits (guide pilot included). */
static void test_integrator_threads_bit_identical(void **state)
{
	const double th[] = { 0, 20, 45, 70 };
	struct tracer_scene s;
	struct tracer_result r1, r2, r3;
	size_t n;

	(void)state;
	sphere_scene(&s, 50, 0.4, 0.5);
	test_trace(&s, th, 4, 20000, 1, &r1);
	test_trace(&s, th, 4, 20000, 2, &r2);
	test_trace(&s, th, 4, 20000, 3, &r3);
	n = (size_t)r1.n_batches * r1.n_theta * TRACER_ORDERS * sizeof(double);
	assert_memory_equal(r1.power, r2.power, n);
	assert_memory_equal(r1.power, r3.power, n);
	assert_memory_equal(r1.energy, r3.energy,
			    r1.n_batches * TRACER_ENERGY_N * sizeof(double));
	tracer_result_free(&r1);
	tracer_result_free(&r2);
	tracer_result_free(&r3);
	tracer_scene_free(&s);
}

/* The lens multiplies by T(incidence angle): linear, clamped past the end
 * (thesis §3.4.4). */
static void test_integrator_lens_transmission(void **state)
{
	double lt[] = { 0.0, 30.0 }, lv[] = { 1.0, 0.4 };
	struct tracer_lens lens = { 2, lt, lv };
	const double th[] = { 0, 15, 20 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_result a, b;
	size_t j;

	(void)state;
	assert_near(tracer_lens_transmission(&lens, 15.0), 0.7, 1e-12);
	assert_near(tracer_lens_transmission(&lens, 80.0), 0.4, 1e-12);
	assert_near(tracer_lens_transmission(&lens, -1.0), 1.0, 1e-12);
	aperture_scene(&s, 5, 3, 10);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 3;
	o.n_paths = 4000;
	o.n_batches = 16;
	assert_int_equal(tracer_trace(&s, &o, &a, NULL), 0);
	o.lens = &lens;
	assert_int_equal(tracer_trace(&s, &o, &b, NULL), 0);
	for (j = 0; j < 3; j++) {
		double pa, pb, sg;

		tracer_result_power(&a, j, 0, &pa, &sg);
		tracer_result_power(&b, j, 0, &pb, &sg);
		/* same paths: exactly the transmission at theta */
		assert_near(pb, pa * tracer_lens_transmission(&lens, th[j]),
			    1e-12 * pa);
	}
	tracer_result_free(&a);
	tracer_result_free(&b);
	tracer_scene_free(&s);
}

/* The detector map integrates to the detector power, and a fully lit
 * pixel sees the beam irradiance times cos(theta); the path dump starts
 * each path on the detector. */
static void test_integrator_map_and_dump(void **state)
{
	const double th[] = { 0, 20 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_result r;
	double sum = 0.0, a_px, p, sg;
	int i, n = 16;

	(void)state;
	aperture_scene(&s, 5, 3, 10);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 2;
	o.n_paths = 64000;
	o.n_batches = 16;
	o.map_n = n;
	o.map_theta_index = 1;
	o.dump_paths = 10;
	assert_int_equal(tracer_trace(&s, &o, &r, NULL), 0);
	a_px = 36.0 / (n * n);
	for (i = 0; i < n * n; i++)
		sum += r.map[i] * a_px;
	tracer_result_power(&r, 1, -1, &p, &sg);
	assert_near(sum / (M_PI * 9.0), p, 1e-9 * p);
	/* a central pixel: all lit at 20 deg (shadow shift 3.6 < 5 - 3) */
	assert_near(r.map[(n / 2) * n + n / 2], cos(20.0 * M_PI / 180.0), 0.05);
	assert_near(r.map[0], 0.0, 0.0);	/* a corner, off the disk */
	for (i = 0; i < 10; i++) {
		assert_true(r.dump_len[i] >= 1);
		assert_near(r.dump[i * TRACER_DUMP_DEPTH].z, -10.0, 1e-6);
		assert_int_equal(r.dump[i * TRACER_DUMP_DEPTH].group, -1);
	}
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* A photometer (acceptance half-angle 10 deg) sees the beam only inside
 * its cone; a rectangular detector wholly under the hole gets cos(theta). */
static void test_integrator_acceptance_and_rect(void **state)
{
	const double th[] = { 0, 5, 15 };
	struct tracer_scene s;
	struct tracer_result r;
	double p, sg;

	(void)state;
	aperture_scene(&s, 5, 3, 10);
	s.det.accept_half_angle_deg = 10.0;
	test_trace(&s, th, 3, 8000, 1, &r);
	tracer_result_power(&r, 1, 0, &p, &sg);
	assert_near(p, cos(5.0 * M_PI / 180.0) *
		    disk_overlap(5, 3, 10 * tan(5.0 * M_PI / 180.0)) /
		    (M_PI * 9.0), 4.0 * sg + 1e-3);
	tracer_result_power(&r, 2, 0, &p, &sg);
	assert_true(p == 0.0);	/* 15 deg is outside the cone */
	tracer_result_free(&r);
	s.det.accept_half_angle_deg = 0.0;
	s.det.shape = TRACER_DET_RECT;
	s.det.half_w_mm = 1.0;
	s.det.half_h_mm = 0.5;
	test_trace(&s, th, 3, 4000, 1, &r);
	tracer_result_power(&r, 2, 0, &p, &sg);
	assert_near(p, cos(15.0 * M_PI / 180.0), 1e-12);
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* Bad options are refused with the field named, not traced. */
static void test_integrator_rejects_bad_options(void **state)
{
	const double bad_th[] = { 0, 200 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_result r;
	struct stray_error err;

	(void)state;
	aperture_scene(&s, 5, 3, 10);
	tracer_trace_defaults(&o);
	o.theta_deg = bad_th;
	o.n_theta = 2;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &r, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "theta_deg");
	assert_near(err.value, 200.0, 0.0);
	o.n_theta = 1;
	o.n_paths = 3;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &r, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "rays");
	tracer_scene_free(&s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_integrator_direct_aperture_overlap),
		cmocka_unit_test(test_integrator_disk_view_factor),
		cmocka_unit_test(test_integrator_sphere_multiplier),
		cmocka_unit_test(test_integrator_energy_bookkeeping),
		cmocka_unit_test(test_integrator_threads_bit_identical),
		cmocka_unit_test(test_integrator_lens_transmission),
		cmocka_unit_test(test_integrator_map_and_dump),
		cmocka_unit_test(test_integrator_acceptance_and_rect),
		cmocka_unit_test(test_integrator_rejects_bad_options),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
