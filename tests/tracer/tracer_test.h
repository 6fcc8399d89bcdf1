/*
 * tracer_test.h - what the tracer tests share: cmocka, a tolerance check
 * that prints both numbers, and small closed-form scenes built through
 * the public mesh API (a plate with a hole, a disk, a sphere with a port).
 */
#ifndef TRACER_TEST_H
#define TRACER_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#include "tracer/integrator.h"
#include "tracer/scene.h"

/* |got - want| <= tol, printing both when not. */
#define assert_near(got, want, tol) do { \
	double g_ = (got), w_ = (want), t_ = (tol); \
	if (!(fabs(g_ - w_) <= t_)) \
		fail_msg("%s = %.9g, expected %.9g +- %.3g", #got, g_, w_, t_); \
	if (getenv("TRACER_TEST_VERBOSE")) \
		print_message("%s = %.6g, expected %.6g +- %.2g\n", #got, \
			      g_, w_, t_); \
} while (0)

/* Ring of n vertices of radius r at height z, or the centre when r = 0. */
static inline uint32_t test_ring(struct tracer_mesh *m, double r, double z,
				 int n)
{
	uint32_t first = 0, idx;
	int j;

	if (r == 0.0) {
		assert_int_equal(tracer_mesh_add_vertex(m, 0, 0, z, &idx, NULL), 0);
		return idx;
	}
	for (j = 0; j < n; j++) {
		double phi = 2.0 * M_PI * j / n;

		assert_int_equal(tracer_mesh_add_vertex(m, r * cos(phi),
				 r * sin(phi), z, &idx, NULL), 0);
		if (j == 0)
			first = idx;
	}
	return first;
}

/* Band between rings (r0, z0) and (r1, z1) of n segments in group g. */
static inline void test_band(struct tracer_mesh *m, double r0, double z0,
			     double r1, double z1, int n, int g)
{
	uint32_t a = test_ring(m, r0, z0, n), b = test_ring(m, r1, z1, n);
	int j;

	for (j = 0; j < n; j++) {
		uint32_t j1 = (uint32_t)((j + 1) % n);

		if (r1 != 0.0)
			assert_int_equal(tracer_mesh_add_triangle(m,
				r0 == 0.0 ? a : a + j, b + j, b + j1, g, NULL), 0);
		if (r0 != 0.0)
			assert_int_equal(tracer_mesh_add_triangle(m, a + j,
				r1 == 0.0 ? b : b + j1, a + j1, g, NULL), 0);
	}
}

/* A detector disk of radius r at c looking along n, whole hemisphere. */
static inline void test_detector(struct tracer_scene *s, double r,
				 struct vec3 c, struct vec3 n)
{
	s->det.shape = TRACER_DET_DISK;
	s->det.center = c;
	s->det.normal = n;
	s->det.radius_mm = r;
	s->det.accept_half_angle_deg = 0.0;
}

/* Area of the overlap of disks of radii a and b, centres s apart. */
static inline double disk_overlap(double a, double b, double s)
{
	double d1, d2;

	if (s >= a + b)
		return 0.0;
	if (s <= fabs(a - b))
		return M_PI * fmin(a, b) * fmin(a, b);
	d1 = (s * s + a * a - b * b) / (2.0 * s);
	d2 = s - d1;
	return a * a * acos(d1 / a) - d1 * sqrt(a * a - d1 * d1) +
	       b * b * acos(d2 / b) - d2 * sqrt(b * b - d2 * d2);
}

/* Trace one scene at the given angles; the caller frees res. */
static inline void test_trace(const struct tracer_scene *s,
			      const double *theta, size_t n, uint64_t paths,
			      int threads, struct tracer_result *res)
{
	struct tracer_trace_opts o;
	struct stray_error err;

	stray_error_clear(&err);
	tracer_trace_defaults(&o);
	o.theta_deg = theta;
	o.n_theta = n;
	o.n_paths = paths;
	o.threads = threads;
	o.n_batches = 32;
	o.seed = 20261122;
	assert_int_equal(tracer_trace(s, &o, res, &err), 0);
}

#endif /* TRACER_TEST_H */
