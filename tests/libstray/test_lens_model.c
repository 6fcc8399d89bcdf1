/*
 * test_lens_model.c - lens curves without lab data (issue 23 item 3): the
 * ideal lens against cos^4 and its field edge; a PST table as FRED or
 * Zemax write it converted with each input-irradiance convention against
 * alpha = PST / PST(0) and PST cos / PST(0) written out by hand; bad
 * tables refused with their line and column.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "../test_util.h"
#include "stray/errfmt.h"
#include "stray/lens_model.h"

static char path[64];

static void put(const char *text)
{
	FILE *f;

	snprintf(path, sizeof(path), "/tmp/stray_pst_%d.csv", (int)getpid());
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static void test_ideal_lens(void **state)
{
	struct stray_curve c;
	size_t i, inside = 0;

	(void)state;
	assert_int_equal(stray_lens_ideal(8.1, &c, NULL), 0);
	for (i = 0; i < c.n; i++) {
		double t = c.theta_deg[i] * (3.14159265358979323846 / 180.0);

		if (i > 0)
			assert_true(c.theta_deg[i] > c.theta_deg[i - 1]);
		if (c.theta_deg[i] <= 8.1 + 1e-12) {
			assert_near(c.alpha[i], pow(cos(t), 4), 1e-15);
			inside++;
		} else {
			assert_near(c.alpha[i], 0.0, 0.0);
		}
	}
	/* 0, 0.25 .. 8.0 (33 rows), the edge 8.1, the step, 90 */
	assert_int_equal(inside, 34);
	assert_int_equal(c.n, 36);
	assert_near(c.theta_deg[c.n - 1], 90.0, 0.0);
	stray_curve_free(&c);
	assert_int_equal(stray_lens_ideal(0.0, &c, NULL), STRAY_EINVAL);
	assert_int_equal(stray_lens_ideal(NAN, &c, NULL), STRAY_EINVAL);
}

/* A PST export: comments, its own column names, a CRLF or two. */
static void test_pst_conventions(void **state)
{
	static const double th[] = { 0, 2.5, 12, 40 };
	static const double pst[] = { 0.42, 0.41, 3.1e-4, 2.2e-7 };
	struct stray_curve beam, ap;
	size_t i;

	(void)state;
	put("# FRED 19 PST analysis, source: collimated, 1 W/mm^2\r\n"
	    "Angle (deg),PST\r\n0,0.42\r\n2.5,0.41\r\n12,3.1e-4\r\n40,2.2e-7\r\n");
	assert_int_equal(stray_lens_from_pst(path, "Angle (deg)", "PST",
					     STRAY_PST_BEAM, &beam, NULL), 0);
	assert_int_equal(stray_lens_from_pst(path, "Angle (deg)", "PST",
					     STRAY_PST_APERTURE, &ap, NULL), 0);
	assert_int_equal(beam.n, 4);
	for (i = 0; i < 4; i++) {
		double c = cos(th[i] * (3.14159265358979323846 / 180.0));

		assert_near(beam.theta_deg[i], th[i], 0.0);
		assert_near(beam.alpha[i], pst[i] / 0.42, 1e-15);
		assert_near(ap.alpha[i], pst[i] * c / 0.42, 1e-15);
	}
	stray_curve_free(&beam);
	stray_curve_free(&ap);
	unlink(path);
}

static void expect_refused(const char *text, const char *want)
{
	struct stray_curve c;
	struct stray_error err;
	char msg[512];

	put(text);
	stray_error_clear(&err);
	assert_int_not_equal(stray_lens_from_pst(path, "theta_deg", "pst",
						 STRAY_PST_BEAM, &c, &err), 0);
	stray_error_format(&err, msg, sizeof(msg));
	if (!strstr(msg, want))
		fail_msg("message '%s' lacks '%s'", msg, want);
	unlink(path);
}

static void test_pst_refused(void **state)
{
	(void)state;
	expect_refused("angle,pst\n0,1\n5,0.5\n", "theta_deg: not in the header");
	expect_refused("theta_deg,pst\n1,1\n5,0.5\n",
		       ":2: theta_deg 1: the first row must be theta 0");
	expect_refused("theta_deg,pst\n0,0\n5,0.5\n",
		       ":2: pst 0: must be > 0 on axis");
	expect_refused("theta_deg,pst\n0,1\n5,-0.5\n", ":3: pst -0.5: must be >= 0");
	expect_refused("theta_deg,pst\n0,1\n5,0.5\n4,0.1\n",
		       ":4: theta_deg 4: angles must increase");
	expect_refused("theta_deg,pst\n0,1\n95,0.5\n",
		       ":3: theta_deg 95: must be in [0, 90) deg");
	expect_refused("theta_deg,pst\n0,1\n", "at least 2 angles");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ideal_lens),
		cmocka_unit_test(test_pst_conventions),
		cmocka_unit_test(test_pst_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
