/*
 * test_frames_sky.c - `stray frames --catalogue CAT --attitude q
 * --truth-stars T.csv` (issue 24): frames of the real sky (the shipped
 * Hipparcos extract) with the list of every star rendered, so other
 * star-tracker software can be scored on them.  The list holds the
 * catalogue's bright stars where the attitude puts them (Vega at the
 * boresight lands on the optical axis), and --catalogue without
 * --attitude is a usage error.  STRAY_BIN=/work/old/bin/stray fails.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../scratch.h"
#include "run_cli.h"

#define CATALOGUE "libstray/data/hip2_hp6.5.dat"
#define PI 3.14159265358979323846

static char work[] = "/tmp/frames_sky_XXXXXX";
static struct cli_run r;

static int setup(void **state)
{
	(void)state;
	return mkdtemp(work) ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(work);
}

/* The attitude that puts the boresight (+z) on (ra, dec): +z of the head
 * = the star's direction, x east, y south (any roll would do). */
static void attitude_to(double ra_deg, double dec_deg, char *q, size_t n)
{
	double a = ra_deg * PI / 180.0, d = dec_deg * PI / 180.0;
	double z[3] = { cos(d) * cos(a), cos(d) * sin(a), sin(d) };
	double x[3] = { -sin(a), cos(a), 0.0 };
	double y[3] = { z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2],
			z[0] * x[1] - z[1] * x[0] };
	/* rows of M (v_head = M v_inertial): x, y, z; q from M (q_c first) */
	double m[3][3] = { { x[0], x[1], x[2] }, { y[0], y[1], y[2] },
			   { z[0], z[1], z[2] } };
	double qc = 0.5 * sqrt(fmax(0.0, 1.0 + m[0][0] + m[1][1] + m[2][2]));

	snprintf(q, n, "%.12f,%.12f,%.12f,%.12f", qc,
		 (m[1][2] - m[2][1]) / (4.0 * qc), (m[2][0] - m[0][2]) / (4.0 * qc),
		 (m[0][1] - m[1][0]) / (4.0 * qc));
}

static void test_truth_stars(void **state)
{
	char q[200], truth[200], line[256];
	char *argv[] = { "stray", "frames", "--alpha", "2e-7", "--attitude", q,
			 "--catalogue", CATALOGUE, "--epoch", "2026.5",
			 "--truth-stars", truth, "--frames", "2", "--json", NULL };
	FILE *f;
	int rows = 0, frame, near_axis = 0;
	double x, y, v, e;

	(void)state;
	/* Vega (HIP 91262), 18h36m56s +38d47' */
	attitude_to(279.2347, 38.7837, q, sizeof(q));
	snprintf(truth, sizeof(truth), "%s/T.csv", work);
	if (run_stray(&r, argv))
		fprintf(stderr, "%s", r.err);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "real catalogue"));
	assert_non_null(f = fopen(truth, "r"));
	assert_non_null(fgets(line, sizeof(line), f));
	assert_string_equal(line, "frame,x_px,y_px,v_mag,electrons\n");
	while (fscanf(f, "%d,%lf,%lf,%lf,%lf", &frame, &x, &y, &v, &e) == 5) {
		rows++;
		assert_true(frame == 0 || frame == 1);
		assert_true(e > 0.0 && v < 7.0);
		/* Vega itself (V 0.09 from its Hp): on the axis, the full
		 * frame's centre (1296, 972), but for its proper motion since
		 * J2000 (~7", a third of a pixel) */
		if (v < 0.3 && fabs(x - 1296.0) < 1.0 && fabs(y - 972.0) < 1.0)
			near_axis++;
	}
	fclose(f);
	assert_true(rows >= 2);
	assert_int_equal(near_axis, 2);	/* once per frame */
}

static void test_catalogue_needs_attitude(void **state)
{
	char *argv[] = { "stray", "frames", "--alpha", "2e-7", "--catalogue",
			 CATALOGUE, NULL };

	(void)state;
	assert_int_equal(run_stray(&r, argv), 2);
	assert_non_null(strstr(r.err, "--catalogue and --truth-stars need --attitude"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_truth_stars),
		cmocka_unit_test(test_catalogue_needs_attitude),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
