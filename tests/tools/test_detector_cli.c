/*
 * test_detector_cli.c - issue 28's detectors carried into the answer and
 * into flight, on the command line: firmware-table builds the named
 * detector's table (version 3) whose Sun angle is `exclusion
 * --detector`'s; orbit and availability fly it, availability refuses a
 * table built for another detector and names an older table's version;
 * diagnose and the review's project file take the detector; `exclusion --models` gives the Sun
 * angle per model with what binds it, the table README.md carries.  Every
 * case fails on the build before (no such option, key or table).
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

/* One stderr line naming each of the words. */
static void expect_bad_naming(const char *a, const char *b, const char *c)
{
	expect_bad(a);
	if (!strstr(r.err, b) || !strstr(r.err, c))
		fail_msg("stderr lacks '%s' or '%s': %s", b, c, r.err);
}

/* The flight table of each detector: its grid, what binds, and the Sun
 * angle `stray exclusion --detector` gives (the module accepted it). */
static void test_firmware_table_detectors(void **state)
{
	static const char *const det[] = { "window", "threshold", "tetra3" };
	static const char *const bind[] = { "lost_stars", "lost_stars",
					    "lost_stars" };
	int i;

	(void)state;
	for (i = 0; i < 3; i++) {
		cJSON *j, *e;

		assert_int_equal(STRAY("firmware-table", "--curve", CURVE,
				       "--detector", (char *)det[i], "--json"), 0);
		j = json_out();
		assert_string_equal(str(j, "detector"), det[i]);
		assert_string_equal(str(j, "binding"), bind[i]);
		assert_true(num(j, "table_version") == 3);
		assert_true(num(j, "detector_grid_nodes") == 72);
		assert_int_equal(STRAY("exclusion", "--curve", CURVE,
				       "--detector", (char *)det[i], "--json"), 0);
		e = json_out();
		assert_true(fabs(num(j, "sun_deg") - num(e, "sun_deg")) < 1e-3);
		assert_true(fabs(num(j, "alpha_required_sun") /
				 num(cJSON_GetObjectItem(e, "sun"),
				     "alpha_required") - 1) < 1e-6);
		cJSON_Delete(j);
		cJSON_Delete(e);
	}
	/* the default is the thesis, as before */
	assert_int_equal(STRAY("firmware-table", "--curve", CURVE, "--json"), 0);
	{
		cJSON *j = json_out();

		assert_string_equal(str(j, "detector"), "thesis");
		assert_true(fabs(num(j, "sun_deg") - 33.863) < 1e-3);
		cJSON_Delete(j);
	}
}

static void write_heads(const char *name, const char *table)
{
	char text[256];

	snprintf(text, sizeof(text), "{\"heads\": [{\"name\": \"A\", "
		 "\"boresight_body\": [0, 0.6, 0.8], \"table\": \"%s\"}]}\n",
		 table);
	put_text(name, text);
}

/* availability flies the table's detector; --detector must match the
 * table, else one line naming the file, the table's detector and the
 * rebuild; an older table's version is named. */
static void test_availability_detector(void **state)
{
	static uint8_t blob[1 << 14];
	FILE *f;
	size_t n;
	cJSON *j, *h;

	(void)state;
	assert_int_equal(STRAY("firmware-table", "--curve", CURVE,
			       "--detector", "window", "--out-bin",
			       in_dir("w.bin")), 0);
	/* stray orbit flies it too and says which detector */
	assert_int_equal(STRAY("orbit", "--table", in_dir("w.bin"), "--hours",
			       "1", "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	cJSON_Delete(j);
	write_heads("h.json", "w.bin");
	assert_int_equal(STRAY("availability", "--write-oem", in_dir("o.oem"),
			       "--write-aem", in_dir("a.aem"), "--hours", "2"), 0);
	assert_int_equal(STRAY("availability", "--oem", in_dir("o.oem"), "--aem",
			       in_dir("a.aem"), "--heads", in_dir("h.json"),
			       "--step-s", "120", "--detector", "window",
			       "--json"), 0);
	j = json_out();
	h = cJSON_GetArrayItem(cJSON_GetObjectItem(j, "heads"), 0);
	assert_string_equal(str(h, "detector"), "window");
	assert_string_equal(str(h, "binding"), "lost_stars");
	cJSON_Delete(j);
	STRAY("availability", "--oem", in_dir("o.oem"), "--aem", in_dir("a.aem"),
	      "--heads", in_dir("h.json"), "--detector", "tetra3");
	expect_bad_naming("w.bin", "detector 'window'", "--detector tetra3");
	STRAY("availability", "--oem", in_dir("o.oem"), "--aem", in_dir("a.aem"),
	      "--heads", in_dir("h.json"), "--detector", "sextractor");
	expect_bad_naming("--detector", "sextractor", "tetra3");

	/* a table of version 2 (before the detectors): named as such */
	f = fopen(in_dir("w.bin"), "rb");
	assert_non_null(f);
	n = fread(blob, 1, sizeof(blob), f);
	fclose(f);
	blob[4] = 2;
	f = fopen(in_dir("v2.bin"), "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(blob, 1, n, f), n);
	fclose(f);
	write_heads("h2.json", "v2.bin");
	STRAY("availability", "--oem", in_dir("o.oem"), "--aem", in_dir("a.aem"),
	      "--heads", in_dir("h2.json"));
	expect_bad_naming("v2.bin", "version '2'", "rebuild");
}

/* diagnose's Sun angle under a named detector, and the thesis as before
 * without one. */
static void test_diagnose_detector(void **state)
{
	char *lab = put_text("lab.csv", "theta_deg,alpha,sigma\n5,1e-3,1e-4\n"
			     "10,1e-4,1e-5\n20,1e-6,1e-7\n40,1e-8,1e-9\n");
	cJSON *j;

	(void)state;
	assert_int_equal(STRAY("diagnose", lab, "--scene", "ref4", "--rays",
			       "2000", "--threads", "1", "--detector", "window",
			       "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "window");
	assert_string_equal(str(j, "sun_binding"), "lost_stars");
	assert_true(fabs(num(j, "sun_alpha_required") / 4.449e-8 - 1) < 1e-3);
	cJSON_Delete(j);
	assert_int_equal(STRAY("diagnose", lab, "--scene", "ref4", "--rays",
			       "2000", "--threads", "1", "--json"), 0);
	j = json_out();
	assert_string_equal(str(j, "detector"), "thesis");
	assert_true(fabs(num(j, "sun_alpha_required") / 3.5209e-7 - 1) < 1e-3);
	cJSON_Delete(j);
	STRAY("diagnose", lab, "--scene", "ref4", "--detector", "x");
	expect_bad_naming("--detector", "'x'", "window");
}

/* The Sun's angle per model (issue 28's closing table) and the same
 * table in README.md, line for line. */
static void test_exclusion_models(void **state)
{
	static const double deg[6] = { 31.83, 33.86, 37.35, 35.34, 36.80,
				       52.27 };
	static const char *const bind[6] = { "false_stars", "false_stars",
		"lost_stars", "lost_stars", "lost_stars", "lost_stars" };
	static char readme[1 << 18];
	char *line, *save = NULL;
	cJSON *j, *m;
	FILE *f;
	size_t n;
	int i = 0, rows = 0;

	(void)state;
	assert_int_equal(STRAY("exclusion", "--curve", CURVE, "--models",
			       "--json"), 0);
	j = json_out();
	cJSON_ArrayForEach(m, cJSON_GetObjectItem(j, "models")) {
		assert_true(i < 6);
		assert_true(fabs(num(m, "sun_deg") - deg[i]) < 0.006);
		assert_string_equal(str(m, "binding"), bind[i]);
		i++;
	}
	assert_int_equal(i, 6);
	cJSON_Delete(j);
	STRAY("exclusion", "--curve", CURVE, "--models", "--detector", "window");
	expect_bad_naming("--models", "--detector", "exclusion");

	/* README.md's table is this command's output */
	assert_int_equal(STRAY("exclusion", "--curve", CURVE, "--models"), 0);
	f = fopen("README.md", "r");
	assert_non_null(f);
	n = fread(readme, 1, sizeof(readme) - 1, f);
	readme[n] = '\0';
	fclose(f);
	for (line = strtok_r(r.out, "\n", &save); line;
	     line = strtok_r(NULL, "\n", &save))
		if (line[0] == '|') {
			if (!strstr(readme, line))
				fprintf(stderr, "not in README.md: %s\n", line);
			assert_non_null(strstr(readme, line));
			rows++;
		}
	assert_int_equal(rows, 8);
}

/* The review's project file names the detector: a bad one is refused
 * naming the key, a good one reaches the exclusion and flight-table
 * steps. */
static void test_review_detector(void **state)
{
	static const char sensor[] = "{\"name\": \"t\"}";
	char proj[512];
	cJSON *j;
	FILE *f;
	static char buf[1 << 16];
	size_t n;

	(void)state;
	put_text("sensor.json", sensor);
	snprintf(proj, sizeof(proj), "{\"sensor\": \"sensor.json\", "
		 "\"scene\": \"ref4\", \"detector\": \"sextractor\", "
		 "\"requirements\": {\"sun_exclusion_deg_max\": 40}}");
	put_text("bad.json", proj);
	STRAY("review", in_dir("bad.json"), "--out", in_dir("rb"));
	expect_bad_naming("bad.json", "detector", "sextractor");
	snprintf(proj, sizeof(proj), "{\"sensor\": \"sensor.json\", "
		 "\"scene\": \"ref4\", \"detector\": \"tetra3\", "
		 "\"detector_sigma\": 5, "
		 "\"requirements\": {\"sun_exclusion_deg_max\": 40}}");
	put_text("p.json", proj);
	assert_int_equal(STRAY("review", in_dir("p.json"), "--out", in_dir("rv"),
			       "--rays", "20000"), 0);
	f = fopen(in_dir("rv/exclusion.json"), "r");
	assert_non_null(f);
	n = fread(buf, 1, sizeof(buf) - 1, f);
	buf[n] = '\0';
	fclose(f);
	j = cJSON_Parse(buf);
	assert_non_null(j);
	assert_string_equal(str(j, "detector"), "tetra3");
	assert_true(num(j, "detector_sigma") == 5);
	assert_string_equal(str(cJSON_GetObjectItem(j, "sun"), "binding"),
			    "lost_stars");
	cJSON_Delete(j);
	f = fopen(in_dir("rv/firmware.json"), "r");
	assert_non_null(f);
	n = fread(buf, 1, sizeof(buf) - 1, f);
	buf[n] = '\0';
	fclose(f);
	j = cJSON_Parse(buf);
	assert_non_null(j);
	assert_string_equal(str(j, "detector"), "tetra3");
	cJSON_Delete(j);
}

static void test_help(void **state)
{
	(void)state;
	assert_int_equal(STRAY("availability", "--help"), 0);
	assert_non_null(strstr(r.out, "--detector"));
	assert_int_equal(STRAY("diagnose", "--help"), 0);
	assert_non_null(strstr(r.out, "--detector"));
	assert_int_equal(STRAY("exclusion", "--help"), 0);
	assert_non_null(strstr(r.out, "--models"));
	assert_int_equal(STRAY("firmware-table", "--help"), 0);
	assert_non_null(strstr(r.out, "tetra3"));
}

static int setup(void **state)
{
	(void)state;
	return cli_setup("detcli");
}

static int teardown(void **state)
{
	(void)state;
	return cli_teardown();
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_firmware_table_detectors),
		cmocka_unit_test(test_availability_detector),
		cmocka_unit_test(test_diagnose_detector),
		cmocka_unit_test(test_exclusion_models),
		cmocka_unit_test(test_review_detector),
		cmocka_unit_test(test_help),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
