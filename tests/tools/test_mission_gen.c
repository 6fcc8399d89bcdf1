/*
 * test_mission_gen.c - the missions `stray availability --write-oem
 * --write-aem` generates for any orbit (issue 25 item 3), read back from
 * the files: the radius is the Earth's plus --altitude-km, the orbit
 * normal gives --inclination-deg (or the sun-synchronous inclination for
 * --ltan), body +z follows the Sun with --attitude sun and stays fixed
 * with --attitude inertial; options that describe no mission refused.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../scratch.h"
#include "../test_util.h"
#include "run_cli.h"

static struct cli_run r;
static char dir[] = "/tmp/stray_missiongenXXXXXX";
static char oem[600], aem[600];

#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })
#define DEG (180.0 / 3.14159265358979323846)

/* The data rows after the last META_STOP: up to max rows of k numbers
 * after the epoch. */
static int rows(const char *path, int k, double (*x)[7], int max)
{
	FILE *f = fopen(path, "r");
	char line[512];
	int n = 0, data = 0;

	assert_non_null(f);
	while (fgets(line, sizeof(line), f) && n < max) {
		char *p = strchr(line, ' ');
		int i;

		if (strncmp(line, "META_STOP", 9) == 0 || strncmp(line, "DATA_START", 10) == 0) {
			data = 1;
			continue;
		}
		if (!data || line[0] < '0' || line[0] > '9' || !p)
			continue;
		for (i = 0; i < k; i++)
			x[n][i] = strtod(p, &p);
		n++;
	}
	fclose(f);
	return n;
}

static void orbit_check(double alt, double incl)
{
	static double x[200][7];
	int n = rows(oem, 6, x, 200), i;

	assert_true(n > 50);
	for (i = 0; i < n; i++) {
		double *s = x[i], h[3] = { s[1] * s[5] - s[2] * s[4],
			s[2] * s[3] - s[0] * s[5], s[0] * s[4] - s[1] * s[3] };

		assert_near(sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), 6378.137 + alt, 1e-3);
		assert_near(acos(h[2] / sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2])) * DEG, incl, 0.01);
	}
}

/* body +z in EME2000 from a CCSDS "LAST" A2B quaternion (x, y, z, w) */
static void body_z(const double *q, double z[3])
{
	double x = q[0], y = q[1], zz = q[2], w = q[3];

	z[0] = 2 * (x * zz - w * y);
	z[1] = 2 * (y * zz + w * x);
	z[2] = 1 - 2 * (x * x + y * y);
}

static void test_inclined_sun_pointing(void **state)
{
	static double q[200][7];
	double z[3], sun[3] = { 0, cos(23.44 / DEG), sin(23.44 / DEG) };
	int n, i;

	(void)state;
	STRAY("availability", "--write-oem", oem, "--write-aem", aem, "--hours", "2",
	      "--altitude-km", "700", "--inclination-deg", "51.6", "--attitude", "sun");
	assert_int_equal(r.status, 0);
	orbit_check(700, 51.6);
	n = rows(aem, 4, q, 200);
	assert_true(n > 50);
	for (i = 0; i < n; i++) {
		body_z(q[i], z);	/* the June solstice Sun: RA 90, dec 23.44 */
		assert_true(acos(z[0] * sun[0] + z[1] * sun[1] + z[2] * sun[2]) * DEG < 0.1);
	}
}

static void test_sso_inertial(void **state)
{
	static double q[200][7];
	double a = 6378.137 + 500, n_rad = sqrt(398600.4418 / (a * a * a));
	double sun_rate = 2 * 3.14159265358979323846 / (365.2421897 * 86400.0);
	double r_e = 6378.137 / a;
	double incl = acos(-sun_rate / (1.5 * n_rad * 1.08262668e-3 * r_e * r_e)) * DEG;
	int n, i, k;

	(void)state;
	STRAY("availability", "--write-oem", oem, "--write-aem", aem, "--hours", "2",
	      "--altitude-km", "500", "--ltan", "10:30", "--attitude", "inertial");
	assert_int_equal(r.status, 0);
	assert_true(incl > 97.3 && incl < 97.5);
	orbit_check(500, incl);
	n = rows(aem, 4, q, 200);
	for (i = 1; i < n; i++)
		for (k = 0; k < 4; k++)
			assert_near(q[i][k], q[0][k], 1e-12);
}

static void test_refused(void **state)
{
	(void)state;
	STRAY("availability", "--write-oem", oem, "--write-aem", aem,
	      "--altitude-km", "90");
	assert_int_equal(r.status, 2);
	assert_non_null(strstr(r.err, "altitude-km"));
	STRAY("availability", "--write-oem", oem, "--write-aem", aem,
	      "--ltan", "10:75");
	assert_int_equal(r.status, 2);
	STRAY("availability", "--write-oem", oem, "--write-aem", aem,
	      "--attitude", "zenith");
	assert_int_equal(r.status, 2);
	assert_non_null(strstr(r.err, "zenith"));
	STRAY("availability", "--oem", oem, "--aem", aem, "--heads", oem,
	      "--inclination-deg", "30");
	assert_int_equal(r.status, 2);
	assert_non_null(strstr(r.err, "write-oem"));
}

static int setup(void **state)
{
	(void)state;
	if (!mkdtemp(dir))
		return -1;
	snprintf(oem, sizeof(oem), "%s/m.oem", dir);
	snprintf(aem, sizeof(aem), "%s/m.aem", dir);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_inclined_sun_pointing),
		cmocka_unit_test(test_sso_inertial),
		cmocka_unit_test(test_refused),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
