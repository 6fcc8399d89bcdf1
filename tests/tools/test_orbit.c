/*
 * test_orbit.c - the demo orbit (mission/orbit.c): a sun-synchronous orbit
 * at 550 km and an anti-nadir attitude, against published values and the
 * flight module's own boresight convention.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../test_util.h"
#include "fdrfw/vec.h"
#include "mission/orbit.h"

#define DEG (180.0 / 3.14159265358979323846)

/* Sun-synchronous inclination at 550 km is 97.59 deg and the period 95.6
 * min (Wertz & Larson, Space Mission Analysis and Design, table B). */
static void test_orbit_sso_inclination_and_period(void **state)
{
	struct orbit o;

	(void)state;
	orbit_sso(&o, 550.0, 22.5, 0.0);
	assert_near(o.incl_rad * DEG, 97.59, 0.02);
	assert_near(2.0 * 3.14159265358979 / o.n_rad_s / 60.0, 95.65, 0.05);
	/* one nodal turn per tropical year */
	assert_near(o.raan_dot_rad_s * 365.2422 * 86400.0 * DEG, 360.0, 1e-4);
}

/* The node sits (ltan - 12) h east of the Sun; the orbit is circular. */
static void test_orbit_node_local_time_and_radius(void **state)
{
	struct orbit o;
	double r[3], v[3], t;

	(void)state;
	orbit_sso(&o, 550.0, 22.5, 1.0);
	orbit_state(&o, 0.0, r, v);
	/* node direction = Sun RA + 10.5 h, compared on the circle */
	t = 1.0 + 10.5 / 24.0 * 2.0 * 3.14159265358979;
	assert_near(r[0] / (ORBIT_RE_KM + 550.0), cos(t), 1e-12);
	assert_near(r[1] / (ORBIT_RE_KM + 550.0), sin(t), 1e-12);
	assert_near(r[2], 0.0, 1e-9);		/* at the ascending node */
	assert_true(v[2] > 0.0);
	for (t = 0.0; t < 86400.0; t += 977.0) {
		orbit_state(&o, t, r, v);
		assert_near(sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]),
			    ORBIT_RE_KM + 550.0, 1e-6);
		assert_near(r[0] * v[0] + r[1] * v[1] + r[2] * v[2], 0.0, 1e-6);
	}
}

/* The quaternion's boresight, by the module's own convention, is the
 * zenith, and the quaternion is a unit one. */
static void test_orbit_anti_nadir_boresight(void **state)
{
	struct orbit o;
	double r[3], v[3], q[4], t, rn;
	float qf[4], b[3];
	int k;

	(void)state;
	orbit_sso(&o, 550.0, 10.5, 2.0);
	for (t = 0.0; t < 6000.0; t += 333.0) {
		orbit_state(&o, t, r, v);
		orbit_anti_nadir_q(r, v, q);
		assert_near(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3],
			    1.0, 1e-12);
		for (k = 0; k < 4; k++)
			qf[k] = (float)q[k];
		fdrfw_boresight(qf, b);
		rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
		for (k = 0; k < 3; k++)
			assert_near(b[k], r[k] / rn, 1e-6);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_orbit_sso_inclination_and_period),
		cmocka_unit_test(test_orbit_node_local_time_and_radius),
		cmocka_unit_test(test_orbit_anti_nadir_boresight),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
