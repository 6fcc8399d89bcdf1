/*
 * test_detectors28.c - issue 28 on the command line: named detectors on
 * fdr, exclusion, sweep and firmware-table, both failure modes in
 * `stray fdr --alpha A --json`, the binding mode in exclusion, and the
 * sensor file naming its detector.  Every case fails on the build before
 * issue 28 (no --detector, no such keys).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <cJSON.h>

#include "cli_fixture.h"

#define CURVE "tests/vectors/fdrfw_curve.csv"

/* The default is the thesis, as before: eq. 2.18's alpha_required. */
static void test_fdr_thesis_default(void **state)
{
	cJSON *j;

	(void)state;
	assert_int_equal(STRAY("fdr", "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "thesis");
	assert_string_equal(str(j, "binding"), "false_stars");
	assert_true(fabs(num(j, "alpha_required") / 3.5209e-7 - 1) < 1e-3);
	cJSON_Delete(j);
}

/* The window sum: the extended false-star model of stray frames (2.1e-7
 * at 5 per image, issue 28), and the DRS lost first. */
static void test_fdr_window_both_modes(void **state)
{
	cJSON *j;
	double af, al;

	(void)state;
	assert_int_equal(STRAY("fdr", "--detector", "window", "--alpha", "1e-7",
			       "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(j, "detector_noise")));
	af = num(j, "alpha_false_stars");
	al = num(j, "alpha_lost_stars");
	assert_true(af > 2.0e-7 && af < 2.3e-7);
	assert_true(al > 0 && al < af);
	assert_string_equal(str(j, "binding"), "lost_stars");
	assert_true(num(j, "alpha_required") == al);
	assert_true(num(j, "false_stars_per_image") < 1e-2);
	assert_true(num(j, "drs_detection_probability") > 0.9 &&
		    num(j, "drs_detection_probability") < 0.95);
	assert_true(fabs(num(j, "limiting_mag") - 5.75) < 0.3);
	cJSON_Delete(j);
}

/* tetra3's k sigma: constant false alarm (no alpha for false stars: null),
 * the DRS ~0.6 at 1e-7 as the rendered frames give; k = 5 loses it
 * sooner. */
static void test_fdr_tetra3(void **state)
{
	cJSON *j;
	double a3, p;

	(void)state;
	assert_int_equal(STRAY("fdr", "--detector", "tetra3", "--alpha", "1e-7",
			       "--json"), 0);
	j = json_out();
	assert_true(cJSON_IsNull(cJSON_GetObjectItem(j, "alpha_false_stars")));
	assert_string_equal(str(j, "binding"), "lost_stars");
	assert_true(num(j, "false_stars_per_image") < 1e-3);
	p = num(j, "drs_detection_probability");
	assert_true(p > 0.5 && p < 0.7);
	assert_true(num(j, "limiting_mag") < 5.75);
	assert_true(num(j, "detector_sigma") == 3);
	a3 = num(j, "alpha_required");
	cJSON_Delete(j);
	assert_int_equal(STRAY("fdr", "--detector", "tetra3", "--detector-sigma",
			       "5", "--json"), 0);
	j = json_out();
	assert_true(num(j, "alpha_required") < a3 / 2);
	cJSON_Delete(j);
}

/* Sky coverage: the fraction of boresights over the (synthetic)
 * catalogue with min_stars stars brighter than the limiting magnitude;
 * falls as tetra3 loses stars; a sensor asking for 40 stars gets little
 * sky; a fractional min_stars is refused. */
static void test_sky_coverage(void **state)
{
	char *m40 = put_text("m40.json", "{\"name\": \"m40\", \"min_stars\": 40}");
	char *mbad = put_text("mbad.json", "{\"name\": \"mb\", \"min_stars\": 2.5}");
	cJSON *j;

	(void)state;
	assert_int_equal(STRAY("fdr", "--detector", "tetra3", "--alpha", "0",
			       "--json"), 0);
	j = json_out();
	assert_true(num(j, "sky_coverage") == 1.0);
	assert_true(num(j, "min_stars") == 4);
	assert_non_null(strstr(str(j, "sky_coverage_stars"), "synthetic"));
	cJSON_Delete(j);
	assert_int_equal(STRAY("fdr", "--detector", "tetra3", "--alpha", "5e-7",
			       "--json"), 0);
	j = json_out();
	assert_true(num(j, "sky_coverage") < 0.9 && num(j, "sky_coverage") > 0.5);
	cJSON_Delete(j);
	assert_int_equal(STRAY("fdr", "--sensor", m40, "--detector", "window",
			       "--alpha", "1e-7", "--json"), 0);
	j = json_out();
	assert_true(num(j, "sky_coverage") < 0.1);
	cJSON_Delete(j);
	assert_int_equal(STRAY("fdr", "--sensor", mbad), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "mbad.json"));
	assert_non_null(strstr(r.err, "min_stars"));
}

/* The fixed pixel threshold: its DRS sits at ~0.95 from 0 to 4e-7 (the
 * component model, detector_blob.c, measured within 0.005 on frames), so
 * lost stars bind (1.3e-7) before false stars (2.4e-7); the rule it
 * replaced said 0.965 and "never". */
static void test_fdr_threshold(void **state)
{
	cJSON *j;

	(void)state;
	assert_int_equal(STRAY("fdr", "--detector", "threshold", "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "binding"), "lost_stars");
	assert_true(num(j, "alpha_required") > 1e-7 &&
		    num(j, "alpha_required") < 1.6e-7);
	assert_true(num(j, "alpha_false_stars") > 2e-7 &&
		    num(j, "alpha_false_stars") < 3.5e-7);
	assert_true(num(j, "pixel_threshold_e") > 40 &&
		    num(j, "pixel_threshold_e") < 60);
	cJSON_Delete(j);
}

/* exclusion: the detector's alpha_required, the binding mode per body,
 * further off axis than the thesis's. */
static void test_exclusion_detector(void **state)
{
	cJSON *j, *sun;
	double thesis_deg, window_deg;

	(void)state;
	assert_int_equal(STRAY("exclusion", "--curve", CURVE, "--json"), 0);
	j = json_out();
	thesis_deg = num(j, "sun_deg");
	cJSON_Delete(j);
	assert_int_equal(STRAY("exclusion", "--curve", CURVE, "--detector",
			       "window", "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	window_deg = num(j, "sun_deg");
	sun = cJSON_GetObjectItem(j, "sun");
	assert_string_equal(str(sun, "binding"), "lost_stars");
	assert_true(num(sun, "alpha_required") == num(sun, "alpha_lost_stars"));
	assert_true(window_deg > thesis_deg + 1);
	cJSON_Delete(j);
	assert_int_equal(STRAY("exclusion", "--curve", CURVE, "--detector",
			       "tetra3"), 0);
	assert_non_null(strstr(r.out, "lost stars bind"));
}

/* sweep answers every design with the detector's alpha_required. */
static void test_sweep_detector(void **state)
{
	char st[128];
	cJSON *j;

	(void)state;
	snprintf(st, sizeof(st), "%s/sweep", dir);
	assert_int_equal(STRAY("sweep", "--scene", "ref4", "--state", st,
			       "--grid", "reflectance=0.02,0.04", "--rays", "1000",
			       "--angles", "0,20,40,60,80", "--detector", "window",
			       "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	assert_string_equal(str(j, "binding"), "lost_stars");
	assert_true(fabs(num(j, "alpha_required") / 4.449e-8 - 1) < 1e-3);
	cJSON_Delete(j);
}

static void test_bad_options(void **state)
{
	(void)state;
	assert_int_equal(STRAY("fdr", "--detector", "sextractor"), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "--detector"));
	assert_int_equal(STRAY("exclusion", "--curve", CURVE,
			       "--detector-sigma", "0.1"), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "--detector-sigma"));
	assert_int_equal(STRAY("sweep", "--help"), 0);
	assert_non_null(strstr(r.out, "--detector"));
}

/* The sensor file names its tracker's detector; a bad one is refused
 * naming the file and the key; firmware-table builds the named detector's
 * table (version 3: its grid, issue 28 item 4; tests/tools/
 * test_detector_cli.c has the rest). */
static void test_sensor_detector(void **state)
{
	char *good = put_text("t5.json",
		"{\"name\": \"t5\", \"detector\": \"tetra3\", "
		"\"detector_sigma\": 5}");
	char *bad = put_text("bad.json", "{\"detector\": \"sextractor\"}");
	char *badk = put_text("badk.json", "{\"detector_sigma\": 100}");
	cJSON *j;

	(void)state;
	assert_int_equal(STRAY("fdr", "--sensor", good, "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "tetra3");
	assert_true(num(j, "detector_sigma") == 5);
	cJSON_Delete(j);
	/* the command line wins */
	assert_int_equal(STRAY("fdr", "--sensor", good, "--detector", "window",
			       "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	cJSON_Delete(j);
	assert_int_equal(STRAY("fdr", "--sensor", bad), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "bad.json"));
	assert_non_null(strstr(r.err, "detector"));
	assert_int_equal(STRAY("fdr", "--sensor", badk), 2);
	assert_non_null(strstr(r.err, "detector_sigma"));
	assert_int_equal(STRAY("firmware-table", "--curve", CURVE, "--json",
			       "--detector", "window"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	cJSON_Delete(j);
	assert_int_equal(STRAY("firmware-table", "--curve", CURVE, "--json",
			       "--sensor", good), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "tetra3");
	assert_true(num(j, "detector_sigma") == 5);
	cJSON_Delete(j);
	assert_int_equal(STRAY("firmware-table", "--curve", CURVE, "--json",
			       "--sensor", good, "--detector", "thesis"), 0);
}

/* A sensor its detector cannot serve is refused naming the file: a window
 * wider than the models' 64 px radius, a star too small for tetra3's
 * 5 px opening to keep (the DRS missed with Pr_drs in the dark). */
static void test_sensor_detector_refused(void **state)
{
	char *big = put_text("big.json",
		"{\"name\": \"big\", \"star_window_px\": 20000}");
	char *small = put_text("small.json",
		"{\"name\": \"small\", \"star_window_px\": 3}");

	(void)state;
	assert_int_equal(STRAY("fdr", "--sensor", big, "--detector", "window"), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "big.json"));
	assert_non_null(strstr(r.err, "window_radius_px"));
	assert_int_equal(STRAY("exclusion", "--curve", CURVE, "--sensor", small,
			       "--detector", "tetra3"), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "small.json"));
	assert_non_null(strstr(r.err, "pr_drs"));
	/* the thesis detector serves both, as before */
	assert_int_equal(STRAY("fdr", "--sensor", small, "--json"), 0);
}

static int setup(void **state)
{
	(void)state;
	return cli_setup("det28");
}

static int teardown(void **state)
{
	(void)state;
	return cli_teardown();
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fdr_thesis_default),
		cmocka_unit_test(test_fdr_window_both_modes),
		cmocka_unit_test(test_fdr_tetra3),
		cmocka_unit_test(test_fdr_threshold),
		cmocka_unit_test(test_sky_coverage),
		cmocka_unit_test(test_exclusion_detector),
		cmocka_unit_test(test_sweep_detector),
		cmocka_unit_test(test_bad_options),
		cmocka_unit_test(test_sensor_detector),
		cmocka_unit_test(test_sensor_detector_refused),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
