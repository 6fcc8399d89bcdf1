/*
 * test_beam_screen.c - the angle screen of the next-event connections
 * (tracer/beam_screen.c) decides as tracer_beam_covers does: every angle
 * it calls YES the exact test covers, every one it calls NO it does not
 * (below a surface's normal: NO whatever the beam), for points in and
 * around ref4's aperture, points put on the beam disk's rim and on the
 * aperture plane (where rounding decides: those must be ASK or right),
 * grazing angles up to 90 deg, one beam and a beam centre per angle
 * (opts.beam_shift_z, the pivot-offset pass); no angle outside
 * tracer_screen_range's arc lights a point.  And it decides: random
 * points leave ASK (the exact test's call) to a few in a million angles,
 * or the screen would cost what it saves, and the arc leaves out most
 * angles.  The comparisons can fail: a margin of 0 or a sign slip in
 * |q|^2 makes rim points disagree, an arc without its margin drops rim
 * points' angles.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "../../tracer/beam_screen.h"
#include "tracer/rng.h"
#include "tracer/scene_load.h"
#include "tracer/source.h"

#define N_ANG 130	/* two blocks and a part */

struct fixture {
	struct tracer_scene s;
	struct tracer_trace_opts o;
	struct worker_ctx w;
	double theta[N_ANG], shift[N_ANG];
	struct vec3 dir[N_ANG];
	double comp[8 * N_ANG];
};

static struct fixture fx;

/* The worker's per-angle arrays as trace.c's run_pass fills them. */
static void setup_angles(int shifted)
{
	struct worker_ctx *w = &fx.w;
	size_t j;

	memset(w, 0, sizeof(*w));
	memset(&fx.o, 0, sizeof(fx.o));
	for (j = 0; j < N_ANG; j++) {
		/* 0..90 in uneven steps, 90 itself and a hair below it */
		fx.theta[j] = j + 2 >= N_ANG ? 90.0 - (N_ANG - 1 - j) * 1e-7 :
			      89.9 * j / (N_ANG - 3);
		fx.shift[j] = shifted ? (double)(j % 7) * 2.5 - 3.0 : 0.0;
	}
	fx.o.theta_deg = fx.theta;
	fx.o.n_theta = N_ANG;
	fx.o.beam_shift_z = shifted ? fx.shift : NULL;
	w->s = &fx.s;
	w->o = &fx.o;
	w->dir = fx.dir;
	w->dir_x = fx.comp;
	w->dir_y = w->dir_x + N_ANG;
	w->dir_z = w->dir_y + N_ANG;
	w->beam_ok = w->dir_z + N_ANG;
	w->direct_ok = w->beam_ok + N_ANG;
	w->beam_cx = w->direct_ok + N_ANG;
	w->beam_cy = w->beam_cx + N_ANG;
	w->beam_cz = w->beam_cy + N_ANG;
	/* as trace.c's run_pass: sorted, the shifts' distinct values */
	tracer_screen_setup(w);
	assert_true(w->angles_sorted);
	assert_int_equal(w->n_shifts, shifted ? 7 : 1);
	for (j = 0; j < N_ANG; j++) {
		struct vec3 d = tracer_source_dir(fx.theta[j]);
		struct vec3 c = v3_sub(fx.s.beam.center,
				       v3_scale(fx.s.beam.normal, fx.shift[j]));

		fx.dir[j] = d;
		w->dir_x[j] = d.x;
		w->dir_y[j] = d.y;
		w->dir_z[j] = d.z;
		w->beam_ok[j] = v3_dot(d, fx.s.beam.normal) > 0.0;
		w->direct_ok[j] = w->beam_ok[j];
		w->beam_cx[j] = c.x;
		w->beam_cy[j] = c.y;
		w->beam_cz[j] = c.z;
	}
}

struct tally {
	long yes, no, ask;	/* ask: not grazing the aperture plane */
	long grazing;		/* d.N <= 1e-6: the exact test's, by design */
	long pruned;		/* outside tracer_screen_range */
};

/* Screen p (normal n or none) against every angle; each YES and NO
 * checked against the exact test. */
static void check_point(struct vec3 p, const struct vec3 *n, struct tally *t)
{
	double keep[TRACER_SCREEN_BLOCK];
	size_t j0, k, lo, hi;

	/* no angle outside the range lights p */
	tracer_screen_range(&fx.w, p, &lo, &hi);
	assert_true(lo <= hi && hi <= N_ANG);
	for (k = 0; k < N_ANG; k++)
		if (k < lo || k >= hi) {
			assert_false(fx.w.beam_ok[k] > 0.0 &&
				     tracer_screen_covers(&fx.w, k, fx.dir[k],
							  p));
			t->pruned++;
		}
	for (j0 = 0; j0 < N_ANG; j0 += TRACER_SCREEN_BLOCK) {
		size_t m = N_ANG - j0 < TRACER_SCREEN_BLOCK ?
			   N_ANG - j0 : TRACER_SCREEN_BLOCK;

		tracer_screen(&fx.w, fx.w.beam_ok, j0, m, p, n, keep);
		for (k = 0; k < m; k++) {
			size_t j = j0 + k;
			bool exact = fx.w.beam_ok[j] > 0.0 &&
				     tracer_screen_covers(&fx.w, j, fx.dir[j], p);

			if (n && v3_dot(fx.dir[j], *n) <= -1e-9) {
				assert_true(keep[k] == TRACER_SCREEN_NO);
				continue;
			}
			if (keep[k] == TRACER_SCREEN_YES) {
				assert_true(exact);
				t->yes++;
			} else if (keep[k] == TRACER_SCREEN_NO) {
				assert_false(exact);
				t->no++;
			} else {
				assert_true(keep[k] == TRACER_SCREEN_ASK);
				if (v3_dot(fx.dir[j], fx.s.beam.normal) > 1e-6)
					t->ask++;
				else
					t->grazing++;
			}
		}
	}
}

/* Points in a box around the aperture (inside the baffle, in front of
 * it), with and without a surface normal. */
static void random_points(struct tracer_rng *g, struct tally *t)
{
	const struct tracer_beam *b = &fx.s.beam;
	int i;

	for (i = 0; i < 4000; i++) {
		double r = 3.0 * b->radius_mm;
		struct vec3 p = v3_add(b->center,
			v3((2.0 * tracer_rng_uniform(g) - 1.0) * r,
			   (2.0 * tracer_rng_uniform(g) - 1.0) * r,
			   -120.0 + 140.0 * tracer_rng_uniform(g)));
		struct vec3 n = v3_norm(v3(tracer_rng_uniform(g) - 0.5,
					   tracer_rng_uniform(g) - 0.5,
					   tracer_rng_uniform(g) - 0.5));

		check_point(p, i % 2 ? &n : NULL, t);
	}
}

/* Points whose line to one angle's source meets its beam disk's rim
 * (or just inside, just outside), or that lie on the aperture plane:
 * where the exact test's own rounding decides. */
static void rim_points(struct tracer_rng *g, struct tally *t)
{
	const struct tracer_beam *b = &fx.s.beam;
	int i;

	for (i = 0; i < 4000; i++) {
		size_t j = (size_t)(tracer_rng_uniform(g) * N_ANG) % N_ANG;
		double ph = 2.0 * M_PI * tracer_rng_uniform(g);
		double f = 1.0 + (i % 3 - 1) * 1e-13, dist;
		struct vec3 c = v3(fx.w.beam_cx[j], fx.w.beam_cy[j],
				   fx.w.beam_cz[j]);
		struct vec3 u = v3(cos(ph), sin(ph), 0.0), q, p;

		/* the ref4 aperture's plane is z = const, normal +z */
		q = v3_add(c, v3_scale(u, f * b->radius_mm));
		dist = i % 4 == 0 ? 0.0 : 150.0 * tracer_rng_uniform(g);
		p = v3_sub(q, v3_scale(fx.dir[j], dist));
		check_point(p, NULL, t);
	}
}

static void run_case(int shifted)
{
	struct tracer_rng g;
	struct tally rnd = { 0, 0, 0, 0, 0 }, rim = { 0, 0, 0, 0, 0 };

	setup_angles(shifted);
	tracer_rng_init(&g, 11 + (uint64_t)shifted, 0);
	random_points(&g, &rnd);
	rim_points(&g, &rim);
	print_message("random points: %ld yes, %ld no, %ld asked, %ld grazing, "
		      "%ld outside the range; rim points: %ld yes, %ld no, "
		      "%ld asked, %ld outside\n", rnd.yes, rnd.no, rnd.ask,
		      rnd.grazing, rnd.pruned, rim.yes, rim.no, rim.ask,
		      rim.pruned);
	/* the range prunes: most random points see the disk over a few
	 * tens of degrees at most */
	assert_true(rnd.pruned * 2 > rnd.yes + rnd.no + rnd.ask + rnd.grazing);
	/* both classes occur, and random points are decided */
	assert_true(rnd.yes > 10000 && rnd.no > 10000);
	assert_true(rnd.ask * 100000 < rnd.yes + rnd.no + rnd.ask);
	/* rim points: decided where rounding cannot matter, asked where
	 * it can (the on-rim third) */
	assert_true(rim.ask > 0);
}

static void test_screen_one_beam(void **state)
{
	(void)state;
	run_case(0);
}

static void test_screen_shifted(void **state)
{
	(void)state;
	run_case(1);
}

static int setup(void **state)
{
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	tracer_scene_init(&fx.s);
	return tracer_scene_load("ref4", NULL, 0, &fx.s, &err);
}

static int teardown(void **state)
{
	(void)state;
	tracer_scene_free(&fx.s);
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_screen_one_beam),
		cmocka_unit_test(test_screen_shifted),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
