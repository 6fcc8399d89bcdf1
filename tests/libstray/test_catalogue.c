/*
 * test_catalogue.c - the synthetic catalogue (stray/catalogue.h): the
 * same sky whatever cone is asked, counts as N(<m), and the ideal camera.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "stray/catalogue.h"

#define MAXS 200000
#define M_PI 3.14159265358979323846
static struct stray_cat_star a[MAXS], b[MAXS];

static void dir_of(double ra, double dec, double u[3])
{
	ra *= M_PI / 180.0;
	dec *= M_PI / 180.0;
	u[0] = cos(dec) * cos(ra);
	u[1] = cos(dec) * sin(ra);
	u[2] = sin(dec);
}

/* A small cone's stars are exactly the big cone's stars inside it. */
static void test_same_sky(void **state)
{
	double d[3], e[3];
	size_t na, nb, i, k, in = 0;

	(void)state;
	dir_of(123.0, 41.0, d);
	dir_of(124.5, 41.5, e);
	stray_catalogue_cone(STRAY_CATALOGUE_SEED, d, 6.0, 9.0, a, MAXS, &na);
	stray_catalogue_cone(STRAY_CATALOGUE_SEED, e, 2.0, 9.0, b, MAXS, &nb);
	assert_true(nb > 0);
	for (i = 0; i < na; i++)
		if (a[i].u[0] * e[0] + a[i].u[1] * e[1] + a[i].u[2] * e[2] >=
		    cos(2.0 * M_PI / 180.0))
			in++;
	assert_int_equal(in, nb);
	for (k = 0; k < nb; k++) {
		int found = 0;

		for (i = 0; i < na && !found; i++)
			found = a[i].ra_deg == b[k].ra_deg &&
				a[i].dec_deg == b[k].dec_deg &&
				a[i].mag == b[k].mag;
		assert_true(found);
	}
	/* another seed is another sky */
	stray_catalogue_cone(STRAY_CATALOGUE_SEED + 1, e, 2.0, 9.0, a, MAXS, &na);
	assert_true(na != nb || a[0].ra_deg != b[0].ra_deg);
}

/* Counts within 4 sigma of N(<m) over a 20 deg cone, at the pole too. */
static void test_counts(void **state)
{
	static const double decs[] = { 0.0, 45.0, 89.0, -80.0 };
	double d[3], area = 2.0 * M_PI * (1.0 - cos(20.0 * M_PI / 180.0)) *
			    pow(180.0 / M_PI, 2.0), expect;
	size_t n, i, j, bright;

	(void)state;
	for (j = 0; j < 4; j++) {
		dir_of(200.0, decs[j], d);
		stray_catalogue_cone(STRAY_CATALOGUE_SEED, d, 20.0, 8.0, a, MAXS, &n);
		expect = (stray_star_counts_per_deg2(8.0) -
			  stray_star_counts_per_deg2(STRAY_CATALOGUE_MAG_MIN)) * area;
		assert_true(fabs((double)n - expect) < 4.0 * sqrt(expect));
		for (i = 0, bright = 0; i < n; i++) {
			assert_true(a[i].mag <= 8.0 && a[i].mag >= -1.5);
			bright += a[i].mag < 6.0;
		}
		expect = (stray_star_counts_per_deg2(6.0) -
			  stray_star_counts_per_deg2(-1.5)) * area;
		assert_true(fabs((double)bright - expect) < 4.0 * sqrt(expect) + 1.0);
	}
}

/* The boresight lands on the axis pixel; 1 deg off lands f tan(1 deg). */
static void test_camera(void **state)
{
	struct stray_camera c = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
				  1000.0, 50.0, 60.0 };
	double u[3] = { 0, 0, 1 }, x, y, t = M_PI / 180.0;

	(void)state;
	assert_true(stray_camera_project(&c, u, &x, &y));
	assert_true(fabs(x - 50.0) < 1e-12 && fabs(y - 60.0) < 1e-12);
	u[0] = sin(t);
	u[2] = cos(t);
	assert_true(stray_camera_project(&c, u, &x, &y));
	assert_true(fabs(x - 50.0 - 1000.0 * tan(t)) < 1e-9);
	u[2] = -1.0;
	assert_false(stray_camera_project(&c, u, &x, &y));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_same_sky),
		cmocka_unit_test(test_counts),
		cmocka_unit_test(test_camera),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
