/*
 * test_user_design.c - issue 23 items 1 and 2 and two defects of issue 31
 * on a new user's design unlike ref4: a 5-vane baffle of 0.5 mm vanes with
 * 45 deg bevels and a 5 % coating, a 1280 x 1024 camera of its own.
 *
 *   - one exclusion verdict: the design fails (its curve stays above the
 *     Sun's alpha_required until the geometric zero at 90 deg), and
 *     `exclusion`, `sweep` and `firmware-table` all say "not excluded"
 *     (null), never 89.98 deg; a spike on axis is refused as a curve;
 *   - `stray diagnose` runs to the end on the user's own trace (its theta 0
 *     row, sigma 0, accepted; the 0.3 mm knife-edge point that does not
 *     fit on a 0.5 mm vane skipped and said), names the hidden coating
 *     against the scene's own nominal 0.05 and the user's sensor;
 *     `--causes` / `--without`; a wide lens no longer "out of memory";
 *   - the surface at fault that explains the residual is a named cause.
 *
 * STRAY_BIN=/path/to/old/stray runs the same checks against another build
 * (how they were shown to fail before the fixes).  Few rays, coarse grids:
 * about 15 s in all.
 */
#include <cJSON.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "../scratch.h"
#include "../test_util.h"
#include "run_cli.h"

static struct cli_run r;
static char dir[64];

#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })

static const char scene_text[] =
	"{ \"type\": \"vanes\",\n"
	"  \"vanes\": [ { \"z\": 0 }, { \"z\": -7 }, { \"z\": -14 },\n"
	"              { \"z\": -21 }, { \"z\": -28 } ],\n"
	"  \"vane_thickness\": 0.5, \"bevel_angle_deg\": 45,\n"
	"  \"bevel_face\": \"lower\", \"edge_radius\": 0,\n"
	"  \"cone_half_angle_deg\": 12,\n"
	"  \"tube\": { \"inner_radius\": 16, \"wall\": 1.2 },\n"
	"  \"pupil\": { \"radius\": 5, \"z\": -36 },\n"
	"  \"reflectance\": 0.05 }\n";

static const char sensor_text[] =
	"{ \"name\": \"user-1280\", \"pixels_x\": 1280, \"pixels_y\": 1024,\n"
	"  \"pixel_pitch_um\": 4.8, \"aperture_diameter_mm\": 10,\n"
	"  \"fov_half_deg\": 12, \"t_exp_s\": 0.1 }\n";

/* ref4 (examples/ref4-vanes.json) with one bevel face 7.5 x too bright. */
static const char ref4_bad_text[] =
	"{ \"type\": \"vanes\",\n"
	"  \"vanes\": [ { \"z\": 0 }, { \"z\": -10 }, { \"z\": -20 }, { \"z\": -30 } ],\n"
	"  \"vane_thickness\": 1, \"bevel_angle_deg\": 45, \"bevel_face\": \"lower\",\n"
	"  \"edge_radius\": 0, \"cone_half_angle_deg\": 10.5,\n"
	"  \"tube\": { \"inner_radius\": 20, \"wall\": 1.5 },\n"
	"  \"pupil\": { \"radius\": 6.5, \"z\": -40 },\n"
	"  \"reflectance\": 0.04, \"exterior_reflectance\": 1, \"beam_margin\": 0.1,\n"
	"  \"accept_half_angle_deg\": 0, \"segments\": 256, \"arc_segments\": 16,\n"
	"  \"materials\": { \"bright\": { \"type\": \"lambert\", \"reflectance\": 0.3 } },\n"
	"  \"groups\": { \"vane2_bevel\": \"bright\" } }\n";

static char *path(const char *name)
{
	static char paths[16][128];
	static int k;
	char *p = paths[k++ % 16];

	snprintf(p, 128, "%s/%s", dir, name);
	return p;
}

static char *put_text(const char *name, const char *text)
{
	char *p = path(name);
	FILE *f = fopen(p, "wb");

	assert_non_null(f);
	assert_int_equal(fwrite(text, 1, strlen(text), f), strlen(text));
	fclose(f);
	return p;
}

/* r.out as JSON (the caller deletes it); fails the test when it is not. */
static cJSON *out_json(void)
{
	cJSON *j = cJSON_Parse(r.out);

	if (!j)
		fail_msg("not JSON (status %d): %.300s / %.300s", r.status,
			 r.out, r.err);
	return j;
}

static const cJSON *at(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);

	if (!v)
		fail_msg("no key '%s' in %.400s", key, r.out);
	return v;
}

static void expect_status(int status, const char *needle)
{
	if (r.status != status || (needle && !strstr(r.err, needle)))
		fail_msg("status %d (wanted %d), stderr: %.600s; wanted '%s'",
			 r.status, status, r.err, needle ? needle : "");
}

static int setup(void **state)
{
	(void)state;
	snprintf(dir, sizeof(dir), "/tmp/stray_user_%d", (int)getpid());
	mkdir(dir, 0700);
	put_text("user5.json", scene_text);
	put_text("cam1280.json", sensor_text);
	put_text("ref4bad.json", ref4_bad_text);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

/* The design's baffle curve to 90 deg (the aperture plane: 0 there). */
static char *user_curve(void)
{
	static char *curve;

	if (!curve) {
		curve = path("user5.csv");
		STRAY("trace", "--scene", path("user5.json"), "--rays", "20000",
		      "--angles", "0:90:5", "--threads", "2", "--out", curve);
		expect_status(0, NULL);
	}
	return curve;
}

/* The failing design: not excluded by the baffle, everywhere alike. */
static void test_exclusion_one_verdict(void **state)
{
	char *curve = user_curve(), *cut = path("cut85.csv");
	cJSON *j;
	FILE *in, *out;
	char line[512];

	(void)state;
	STRAY("exclusion", "--curve", curve, "--sensor", path("cam1280.json"),
	      "--json");
	expect_status(0, NULL);
	j = out_json();
	assert_true(cJSON_IsNull(at(j, "sun_deg")));
	assert_true(cJSON_IsFalse(at(at(j, "sun"), "excluded_within_curve")));
	assert_non_null(strstr(at(at(j, "sun"), "reason")->valuestring,
			       "aperture plane"));
	assert_true(cJSON_IsNumber(at(j, "moon_deg")));	/* the Moon is */
	cJSON_Delete(j);

	STRAY("sweep", "--scene", path("user5.json"), "--sensor",
	      path("cam1280.json"), "--grid", "reflectance=0.05", "--rays",
	      "20000", "--angles", "0:90:5", "--threads", "2", "--state",
	      path("sweep.d"), "--json");
	expect_status(0, NULL);
	j = out_json();
	assert_true(cJSON_IsNull(at(cJSON_GetArrayItem(at(j, "designs"), 0),
				    "sun_deg")));
	cJSON_Delete(j);

	STRAY("firmware-table", "--curve", curve, "--sensor",
	      path("cam1280.json"), "--out-bin", path("t.bin"), "--json");
	expect_status(0, NULL);
	j = out_json();
	assert_true(cJSON_IsNull(at(j, "sun_deg")));
	assert_true(cJSON_IsFalse(at(j, "sun_excluded")));
	/* what the table flies: the aperture plane, the Sun in front
	 * blinds the tracker (firmware_fdr/README.md) */
	assert_near(at(j, "table_exclusion_sun_deg")->valuedouble, 90.0, 1e-4);
	cJSON_Delete(j);

	/* the same curve cut before the plane: the same verdict; no flight
	 * table can place the Sun (refused, one line) */
	in = fopen(curve, "r");
	out = fopen(cut, "w");
	assert_non_null(in);
	assert_non_null(out);
	while (fgets(line, sizeof(line), in))
		if (strncmp(line, "90,", 3) != 0)
			fputs(line, out);
	fclose(in);
	fclose(out);
	STRAY("exclusion", "--curve", cut, "--sensor", path("cam1280.json"),
	      "--json");
	expect_status(0, NULL);
	j = out_json();
	assert_true(cJSON_IsNull(at(j, "sun_deg")));
	cJSON_Delete(j);
	STRAY("firmware-table", "--curve", cut, "--sensor",
	      path("cam1280.json"), "--out-bin", path("t2.bin"));
	expect_status(2, "not excluded by the baffle");
	assert_int_equal(r.err_lines, 1);
}

/* `stray availability` flies the design's table: it says, per head, that
 * the baffle never excludes the Sun (libstray's verdict on the table). */
static void test_availability_says_so(void **state)
{
	char *oem = path("o.oem"), *aem = path("a.aem"), *heads;
	FILE *f;
	cJSON *j;
	int i;

	(void)state;
	STRAY("firmware-table", "--curve", user_curve(), "--sensor",
	      path("cam1280.json"), "--out-bin", path("user.bin"));
	expect_status(0, NULL);
	f = fopen(oem, "w");
	assert_non_null(f);
	fprintf(f, "CCSDS_OEM_VERS = 2.0\nCREATION_DATE = 2026-03-01T00:00:00\n"
		"ORIGINATOR = test\nMETA_START\nOBJECT_NAME = T\nOBJECT_ID = T\n"
		"CENTER_NAME = EARTH\nREF_FRAME = EME2000\nTIME_SYSTEM = UTC\n"
		"INTERPOLATION = LAGRANGE\nINTERPOLATION_DEGREE = 1\nMETA_STOP\n");
	for (i = 0; i < 4; i++) {
		double u = 0.6 * i;

		fprintf(f, "2026-03-20T00:%02d:00 %.6f %.6f %.6f %.6f %.6f %.6f\n",
			10 * i, 7000 * cos(u), 4200 * sin(u), 5600 * sin(u),
			-7.0 * sin(u), 4.2 * cos(u), 5.6 * cos(u));
	}
	fclose(f);
	f = fopen(aem, "w");
	assert_non_null(f);
	fprintf(f, "CCSDS_AEM_VERS = 1.0\nCREATION_DATE = 2026-03-01T00:00:00\n"
		"ORIGINATOR = test\nMETA_START\nOBJECT_NAME = T\nOBJECT_ID = T\n"
		"REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\nATTITUDE_DIR = B2A\n"
		"TIME_SYSTEM = UTC\nATTITUDE_TYPE = QUATERNION\n"
		"QUATERNION_TYPE = FIRST\nMETA_STOP\nDATA_START\n");
	for (i = 0; i < 4; i++)
		fprintf(f, "2026-03-20T00:%02d:00 1 0 0 0\n", 10 * i);
	fprintf(f, "DATA_STOP\n");
	fclose(f);
	heads = put_text("heads.json", "{\"heads\": [{\"name\": \"U\", "
			 "\"boresight_body\": [0, 0, 1], \"table\": \"user.bin\"}]}\n");
	STRAY("availability", "--oem", oem, "--aem", aem, "--heads", heads,
	      "--step-s", "600", "--json");
	expect_status(0, NULL);
	j = out_json();
	assert_true(cJSON_IsFalse(at(cJSON_GetArrayItem(at(j, "heads"), 0),
				     "sun_excluded_by_baffle")));
	cJSON_Delete(j);
}

/* A curve zero everywhere but on axis is no baffle's curve. */
static void test_spike_refused(void **state)
{
	char *spike = put_text("spike.csv",
			       "theta_deg,alpha\n0,1\n1,0\n30,0\n90,0\n");

	(void)state;
	STRAY("firmware-table", "--curve", spike, "--out-bin", path("s.bin"));
	expect_status(2, "spike");
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "spike.csv"));
	STRAY("exclusion", "--curve", spike);
	expect_status(2, "spike");
}

/* The user's own trace as the measurement: hidden coating 0.09. */
static char *user_measured(void)
{
	static char *m;

	if (!m) {
		m = path("measured.csv");
		STRAY("trace", "--scene", path("user5.json"), "--set",
		      "reflectance=0.09", "--rays", "100000", "--angles",
		      "0,5,10,15,20:88:4", "--threads", "2", "--out", m);
		expect_status(0, NULL);
	}
	return m;
}

static void test_diagnose_user_scene(void **state)
{
	const cJSON *c, *causes, *notes;
	int found = 0, skipped = 0;
	cJSON *j;

	(void)state;
	STRAY("diagnose", user_measured(), "--scene", path("user5.json"),
	      "--sensor", path("cam1280.json"), "--rays", "20000", "--json");
	expect_status(0, NULL);
	j = out_json();
	assert_string_equal(at(j, "sensor")->valuestring, "user-1280");
	assert_true(cJSON_IsTrue(at(j, "normalised")));
	assert_true(cJSON_IsTrue(at(j, "explained")));
	causes = at(j, "causes");
	cJSON_ArrayForEach(c, causes)
		if (strcmp(at(c, "name")->valuestring, "reflectance") == 0) {
			const cJSON *p = at(c, "params");

			assert_near(at(at(c, "nominal"), "reflectance")->valuedouble,
				    0.05, 1e-9);
			assert_near(at(p, "reflectance")->valuedouble, 0.09,
				    0.015);
			found = 1;
		}
	assert_true(found);
	notes = at(j, "scene_notes");
	cJSON_ArrayForEach(c, notes)
		skipped |= strstr(c->valuestring, "knife_edge_radius") &&
			   strstr(c->valuestring, "skipped");
	assert_true(skipped);
	cJSON_Delete(j);

	/* in words: the scene's nominal, the user's camera */
	STRAY("diagnose", user_measured(), "--scene", path("user5.json"),
	      "--sensor", path("cam1280.json"), "--rays", "20000",
	      "--causes", "reflectance,knife_edge_radius");
	expect_status(0, NULL);
	assert_non_null(strstr(r.out, "(nominal 0.05)"));
	assert_non_null(strstr(r.out, "In orbit (user-1280"));
	assert_null(strstr(r.out, "floor "));	/* only the two asked for */
}

static void test_diagnose_cause_choice(void **state)
{
	const cJSON *single;
	cJSON *j;

	(void)state;
	STRAY("diagnose", user_measured(), "--scene", path("user5.json"),
	      "--rays", "20000", "--without", "floor,light_leak,knife_edge_radius",
	      "--json");
	expect_status(0, NULL);
	j = out_json();
	single = at(j, "single");
	assert_null(cJSON_GetObjectItemCaseSensitive(single, "floor"));
	assert_null(cJSON_GetObjectItemCaseSensitive(single, "knife_edge_radius"));
	assert_non_null(cJSON_GetObjectItemCaseSensitive(single, "reflectance"));
	cJSON_Delete(j);
	STRAY("diagnose", user_measured(), "--scene", path("user5.json"),
	      "--without", "no_such_cause");
	expect_status(2, "no_such_cause");
	assert_int_equal(r.err_lines, 1);
}

/* Issue 31: a lens above half its on-axis value to 45 deg computed a
 * negative bin count ("out of memory", exit 1); one above half to 90
 * deg has no out-of-field part: refused, naming the file. */
static void test_diagnose_wide_lens(void **state)
{
	char *wide = put_text("wide.csv", "theta_deg,alpha\n0,1\n10,0.9\n"
			      "40,0.8\n45,0.6\n50,0.1\n90,0.01\n");
	char *flat = put_text("flat.csv", "theta_deg,alpha\n0,1\n30,0.9\n"
			      "90,0.8\n");

	char *meas = path("photometer.csv");

	(void)state;
	/* a photometer's curve (sigma > 0 everywhere): the lens alone */
	STRAY("photometer", "--truth", user_measured(), "--out", meas,
	      "--floor", "1e-9", "--detect-floor", "1e-9");
	expect_status(0, NULL);
	STRAY("diagnose", meas, "--scene", path("user5.json"), "--rays",
	      "20000", "--lens", wide, "--json");
	expect_status(0, NULL);
	STRAY("diagnose", meas, "--scene", path("user5.json"), "--rays",
	      "20000", "--lens", flat);
	expect_status(2, "flat.csv");
	assert_non_null(strstr(r.err, "90 deg"));
}

/* ref4 with one bevel face too bright: the surface at fault explains
 * the residual, so it is a named cause and the verdict says explained. */
static void test_surface_verdict(void **state)
{
	char *truth = path("bad_truth.csv"), *meas = path("bad_meas.csv");
	const cJSON *c;
	int named = 0;
	cJSON *j;

	(void)state;
	STRAY("trace", "--scene", path("ref4bad.json"), "--rays", "200000",
	      "--angles", "0:30:5,30:85:5", "--threads", "2", "--out", truth);
	expect_status(0, NULL);
	STRAY("photometer", "--truth", truth, "--out", meas, "--floor", "1e-9",
	      "--detect-floor", "1e-9");
	expect_status(0, NULL);
	STRAY("diagnose", meas, "--scene", "ref4", "--rays", "20000",
	      "--threads", "2", "--json");
	expect_status(0, NULL);
	j = out_json();
	cJSON_ArrayForEach(c, at(j, "causes"))
		named |= cJSON_IsString(cJSON_GetObjectItemCaseSensitive(c,
					"surface")) &&
			 strcmp(at(c, "surface")->valuestring,
				"vane2_bevel") == 0;
	assert_true(named);
	assert_true(cJSON_IsTrue(at(j, "explained")));
	assert_string_equal(at(cJSON_GetArrayItem(at(at(j, "surfaces"),
				"groups"), 0), "group")->valuestring,
			    "vane2_bevel");
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_exclusion_one_verdict),
		cmocka_unit_test(test_availability_says_so),
		cmocka_unit_test(test_spike_refused),
		cmocka_unit_test(test_diagnose_user_scene),
		cmocka_unit_test(test_diagnose_cause_choice),
		cmocka_unit_test(test_diagnose_wide_lens),
		cmocka_unit_test(test_surface_verdict),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
