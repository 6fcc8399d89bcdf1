/*
 * test_ephem.c - the on-board Sun and Moon against ERFA (SOFA's
 * eraEpv00, VSOP2000-based, and eraMoon98, Meeus ch. 47 in full) over
 * 2020-2040: Sun within 0.01 deg, Moon within 0.1 deg (issue #6).
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>
#include <erfa.h>
#include <erfam.h>

#include "fdrfw/ephem.h"

#define J2000_JD 2451545.0
#define DAY_S 86400.0
/* 2020-01-01 0h and 2041-01-01 0h TT, in days from J2000. */
#define START_D 7304.5
#define END_D 15005.5
/* A step incommensurate with the day and the month, ~14000 epochs. */
#define STEP_D 0.5471

static double angle_deg(double a[3], const float b[3])
{
	double bb[3] = { b[0], b[1], b[2] }, c[3];

	eraPxp(a, bb, c);
	return atan2(eraPm(c), eraPdp(a, bb)) * ERFA_DR2D;
}

struct stats {
	double max, sum2;
	long n;
};

static void add(struct stats *s, double e)
{
	s->max = e > s->max ? e : s->max;
	s->sum2 += e * e;
	s->n++;
}

static void test_sun_within_001_deg(void **state)
{
	struct stats s = { 0, 0, 0 };
	double d;

	(void)state;
	for (d = START_D; d < END_D; d += STEP_D) {
		int32_t t = (int32_t)lround(d * DAY_S);
		double pvh[2][3], pvb[2][3], sun[3];
		float u[3];

		eraEpv00(J2000_JD, t / DAY_S, pvh, pvb);
		eraSxp(-1.0, pvh[0], sun);	/* Earth -> Sun, geometric */
		fdrfw_sun_dir(t, u);
		add(&s, angle_deg(sun, u));
	}
	printf("sun vs eraEpv00 2020-2040: max %.5f deg, rms %.5f deg, n %ld\n",
	       s.max, sqrt(s.sum2 / s.n), s.n);
	assert_true(s.n > 10000);
	assert_true(s.max <= 0.01);
}

static void test_moon_within_01_deg(void **state)
{
	struct stats s = { 0, 0, 0 }, r = { 0, 0, 0 };
	double d;

	(void)state;
	for (d = START_D; d < END_D; d += STEP_D) {
		int32_t t = (int32_t)lround(d * DAY_S);
		double pv[2][3];
		float m[3];

		eraMoon98(J2000_JD, t / DAY_S, pv);
		fdrfw_moon_pos_km(t, m);
		add(&s, angle_deg(pv[0], m));
		/* Distance, for the lunar parallax: within 0.5% (~2000 km). */
		add(&r, fabs(sqrt((double)m[0] * m[0] + (double)m[1] * m[1] +
				  (double)m[2] * m[2]) /
			     (eraPm(pv[0]) * ERFA_DAU / 1e3) - 1.0));
	}
	printf("moon vs eraMoon98 2020-2040: max %.4f deg, rms %.4f deg; "
	       "distance max rel %.2e, n %ld\n", s.max, sqrt(s.sum2 / s.n),
	       r.max, s.n);
	assert_true(s.max <= 0.1);
	assert_true(r.max <= 5e-3);
}

/* Fixed-point time: t and t + 60 s give directions 60 s of lunar motion
 * apart, also near the end of the int32 range (2063): a float t in
 * seconds would step by 128 s there. */
static void test_time_resolution(void **state)
{
	int32_t ts[] = { 0, 631152000, 1262304000, 2000000000 };
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(ts) / sizeof(ts[0]); i++) {
		float a[3], b[3];
		double da[3], db[3], c[3], ang;
		int k;

		fdrfw_moon_pos_km(ts[i], a);
		fdrfw_moon_pos_km(ts[i] + 60, b);
		for (k = 0; k < 3; k++) {
			da[k] = a[k];
			db[k] = b[k];
		}
		eraPxp(da, db, c);
		ang = asin(eraPm(c) / (eraPm(da) * eraPm(db))) * ERFA_DR2D;
		/* The Moon moves 11.8-15.4 deg/day: 60 s = 0.0082-0.0107 deg. */
		assert_true(ang > 0.0075 && ang < 0.0115);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sun_within_001_deg),
		cmocka_unit_test(test_moon_within_01_deg),
		cmocka_unit_test(test_time_resolution),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
