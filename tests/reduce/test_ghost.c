/*
 * test_ghost.c - secondary maxima of row-collapsed profiles and their
 * tracks over angle (thesis fig. 3.9, reflections A and B).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

#include "stray/reduce_ghost.h"
#include "test_util.h"

#define NC 128

static double scratch[5 * NC + 64];

/* A ramp from 100 to 300 with a Bayer colour ripple of +/-1%. */
static void base(double *p, double *v)
{
	size_t c;

	for (c = 0; c < NC; c++) {
		p[c] = (100.0 + 200.0 * c / (NC - 1.0)) * (c % 2 ? 1.01 : 0.99);
		v[c] = 0.01;
	}
}

static void bump(double *p, double centre, double amp)
{
	size_t c;

	for (c = 0; c < NC; c++)
		p[c] += amp * exp(-0.5 * (c - centre) * (c - centre) / 4.0);
}

static void test_ghost_none_on_ramp_with_colour(void **state)
{
	double p[NC], v[NC];
	struct stray_ghost_opts o;
	struct stray_ghost_peak pk[4];

	(void)state;
	stray_ghost_opts_default(&o);
	assert_true(stray_ghost_scratch(NC, &o) <= sizeof(scratch) / sizeof(double));
	base(p, v);
	assert_int_equal(stray_ghost_find(p, v, NC, &o, scratch, pk, 4), 0);
}

static void test_ghost_finds_bump_centroid_and_power(void **state)
{
	double p[NC], v[NC];
	struct stray_ghost_opts o;
	struct stray_ghost_peak pk[4];
	size_t n;

	(void)state;
	stray_ghost_opts_default(&o);
	base(p, v);
	bump(p, 40.3, 20.0);
	n = stray_ghost_find(p, v, NC, &o, scratch, pk, 4);
	assert_int_equal(n, 1);
	assert_near(pk[0].column, 40.3, 0.3);
	/* Gaussian area amp sigma sqrt(2 pi), sigma = 2 columns */
	assert_near(pk[0].excess, 20.0 * 2.0 * sqrt(2.0 * 3.141592653589793), 10.0);
	assert_true(pk[0].z > 100.0);
}

static void test_ghost_tracks_two_reflections(void **state)
{
	struct stray_ghost_opts o;
	struct stray_ghost_point pts[4][16];
	struct stray_ghost_track tr[4];
	struct stray_ghost_tracker t;
	int a, k;

	(void)state;
	stray_ghost_opts_default(&o);
	for (k = 0; k < 4; k++)
		tr[k] = (struct stray_ghost_track){ 0, 16, pts[k], 0 };
	stray_ghost_tracker_init(&t, &o, tr, 4);
	for (a = 0; a < 10; a++) {
		struct stray_ghost_peak pk[3];
		size_t n = 0;

		if (a != 4)	/* A missed at one angle: the track bridges */
			pk[n++] = (struct stray_ghost_peak){ 10.0 + 5.0 * a, 1, 50 };
		if (a >= 3)
			pk[n++] = (struct stray_ghost_peak){ 100.0 - 4.0 * a, 1, 40 };
		if (a == 6)	/* a lone false peak */
			pk[n++] = (struct stray_ghost_peak){ 70.0, 1, 10 };
		stray_ghost_tracker_add(&t, a, pk, n, 1.0, 100.0);
	}
	assert_int_equal(stray_ghost_tracker_finish(&t), 2);
	assert_int_equal(tr[0].n, 9);
	assert_int_equal(tr[1].n, 7);
	assert_near(tr[0].pt[4].column, 10.0 + 5.0 * 5, 1e-12);
	assert_near(tr[1].pt[0].theta_deg, 3.0, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ghost_none_on_ramp_with_colour),
		cmocka_unit_test(test_ghost_finds_bump_centroid_and_power),
		cmocka_unit_test(test_ghost_tracks_two_reflections),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
