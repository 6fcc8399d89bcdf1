/*
 * test_firmware_table.c - `stray firmware-table` as a user runs it: the
 * blob and the C source it writes, its JSON summary, and one-line errors
 * for bad input (docs/cli.md: exit 2 bad input, 1 other failures).
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>

#include <cmocka.h>
#include <cJSON.h>

#include "../scratch.h"
#include "../tools/run_cli.h"
#include "fdrfw/table_build.h"
#include "fixture.h"
#include "stray/curve_io.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

#define CURVE "tests/vectors/fdrfw_curve.csv"

static char dir[] = "/tmp/fdrfw_cli_XXXXXX";

static int setup(void **state)
{
	(void)state;
	return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

static void test_help(void **state)
{
	static struct cli_run r;
	char *argv[] = { "stray", "firmware-table", "--help", NULL };

	(void)state;
	assert_int_equal(run_stray(&r, argv), 0);
	assert_non_null(strstr(r.out, "usage: stray firmware-table"));
	assert_string_equal(r.err, "");
}

/* The blob is the table libstray builds in-process from the same file,
 * byte for byte, and passes the module's own check. */
static void test_blob_and_c_source(void **state)
{
	static struct cli_run r;
	static uint8_t blob[FDRFW_BLOB_SIZE + 1], want[FDRFW_BLOB_SIZE];
	static char csrc[1 << 16];
	char bin[256], src[256];
	char *argv[] = { "stray", "firmware-table", "--curve", CURVE,
			 "--out-bin", bin, "--out-c", src, NULL };
	struct fdrfw_build_params p = {
		.hysteresis_deg = FDRFW_BUILD_HYSTERESIS_DEG,
		.earth_albedo = FDRFW_BUILD_ALBEDO,
	};
	struct fdrfw_table got, t;
	struct stray_curve c;
	struct stray_curve_view v;
	char crc[32];
	FILE *f;
	size_t n;

	(void)state;
	snprintf(bin, sizeof(bin), "%s/t.bin", dir);
	snprintf(src, sizeof(src), "%s/t.c", dir);
	assert_int_equal(run_stray(&r, argv), 0);
	f = fopen(bin, "rb");
	assert_non_null(f);
	n = fread(blob, 1, sizeof(blob), f);
	fclose(f);
	assert_int_equal(n, FDRFW_BLOB_SIZE);
	assert_int_equal(fdrfw_table_parse(blob, n, &got), FDRFW_OK);
	assert_int_equal(fdrfw_table_check(&got), FDRFW_OK);

	assert_int_equal(stray_curve_load(CURVE, &c, NULL), 0);
	v = stray_curve_view_of(&c);
	p.f_sun_ph_s_m2 = fixture_fluxes()->sun;
	p.f_moon_full_ph_s_m2 = fixture_fluxes()->moon;
	p.f_drs_ph_s_m2 = fixture_fluxes()->drs;
	assert_int_equal(fdrfw_table_build(&v, stray_sensor_st16_like(), &p,
					   &t, NULL), 0);
	stray_curve_free(&c);
	fdrfw_table_serialize(&t, want);
	assert_memory_equal(blob, want, FDRFW_BLOB_SIZE);

	f = fopen(src, "r");
	assert_non_null(f);
	n = fread(csrc, 1, sizeof(csrc) - 1, f);
	csrc[n] = '\0';
	fclose(f);
	assert_non_null(strstr(csrc, "const struct fdrfw_table "
				     "fdrfw_flight_table = {"));
	snprintf(crc, sizeof(crc), ".crc32 = 0x%08lXu", (unsigned long)t.crc32);
	assert_non_null(strstr(csrc, crc));
}

static void test_json_summary(void **state)
{
	static struct cli_run r;
	char *argv[] = { "stray", "firmware-table", "--curve", CURVE,
			 "--json", NULL };
	struct fdrfw_table t;
	cJSON *o;

	(void)state;
	assert_int_equal(run_stray(&r, argv), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	fixture_table(&t);
	assert_near(cJSON_GetObjectItem(o, "sun_deg")->valuedouble,
		    (double)t.exclusion_sun_deg, 1e-3);
	assert_near(cJSON_GetObjectItem(o, "n_curve")->valuedouble, 86, 0);
	assert_near(cJSON_GetObjectItem(o, "blob_bytes")->valuedouble,
		    FDRFW_BLOB_SIZE, 0);
	assert_non_null(cJSON_GetObjectItem(o, "crc32"));
	cJSON_Delete(o);
}

/* The summary of one `stray firmware-table --json [--normalisation N]`. */
static cJSON *summary_json(char *normalisation)
{
	static struct cli_run r;
	char *argv[] = { "stray", "firmware-table", "--curve", CURVE, "--json",
			 normalisation ? "--normalisation" : NULL,
			 normalisation, NULL };
	cJSON *o;

	assert_int_equal(run_stray(&r, argv), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	return o;
}

static double json_num(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItem(o, key);

	assert_non_null(v);
	return v->valuedouble;
}

/* eq. 2.3's k_px from the st16-like data sheet (ref4-baffle.md: 13 mm
 * aperture, 2592 x 1944 pixels of 2.2 um), written out here: the table
 * carries it, or 1 with --normalisation thesis.  The Gaussian FDR depends
 * on alpha only through I_px = alpha F t A_px k_px, so the thesis's
 * alpha_required is k_px times the consistent one. */
static void test_normalisation(void **state)
{
	const double k_px = 3.14159265358979 * 6.5 * 6.5 /
			    (2592.0 * 1944.0 * 2.2e-3 * 2.2e-3);
	cJSON *c = summary_json(NULL), *cc = summary_json("consistent");
	cJSON *th = summary_json("thesis");

	(void)state;
	assert_string_equal(cJSON_GetObjectItem(c, "normalisation")->valuestring,
			    "consistent");
	assert_string_equal(cJSON_GetObjectItem(th, "normalisation")->valuestring,
			    "thesis");
	assert_near(json_num(c, "k_px"), k_px, 1e-5 * k_px);
	assert_near(json_num(cc, "k_px"), json_num(c, "k_px"), 0);
	assert_near(json_num(th, "k_px"), 1.0, 0);
	assert_near(json_num(th, "alpha_required_sun") /
		    json_num(c, "alpha_required_sun"), k_px, 1e-5 * k_px);
	/* less light tolerated per pixel: the Sun is excluded further out */
	assert_true(json_num(c, "sun_deg") > json_num(th, "sun_deg"));
	cJSON_Delete(c);
	cJSON_Delete(cc);
	cJSON_Delete(th);
}

/* `stray orbit` says which normalisation its table carries, and refuses a
 * table built with another than the one it is asked for. */
static void test_orbit_normalisation(void **state)
{
	static struct cli_run r;
	char bin[256];
	char *build[] = { "stray", "firmware-table", "--curve", CURVE,
			  "--normalisation", "thesis", "--out-bin", bin, NULL };
	char *fly[] = { "stray", "orbit", "--table", bin, "--hours", "1",
			"--step-s", "60", "--json", NULL };
	char *want[] = { "stray", "orbit", "--table", bin, "--hours", "1",
			 "--normalisation", "consistent", NULL };
	cJSON *o;

	(void)state;
	snprintf(bin, sizeof(bin), "%s/thesis.bin", dir);
	assert_int_equal(run_stray(&r, build), 0);
	assert_int_equal(run_stray(&r, fly), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	assert_string_equal(cJSON_GetObjectItem(o, "normalisation")->valuestring,
			    "thesis");
	assert_near(json_num(o, "k_px"), 1.0, 0);
	cJSON_Delete(o);
	assert_int_equal(run_stray(&r, want), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "thesis.bin: k_px"));
}

/* A bad input: the expected exit status, one stderr line with `what`. */
static void expect_error(char *const argv[], int status, const char *what)
{
	static struct cli_run r;

	assert_int_equal(run_stray(&r, argv), status);
	assert_int_equal(r.err_lines, 1);
	if (!strstr(r.err, what))
		fail_msg("stderr '%s' does not name '%s'", r.err, what);
}

static void write_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static void test_bad_input(void **state)
{
	char nan_curve[256], long_curve[256], out[256], text[8192];
	char *no_curve[] = { "stray", "firmware-table", "--out-bin", "x", NULL };
	char *missing[] = { "stray", "firmware-table", "--curve",
			    "/nonexistent/c.csv", "--json", NULL };
	char *nan_run[] = { "stray", "firmware-table", "--curve", nan_curve,
			    "--json", NULL };
	char *long_run[] = { "stray", "firmware-table", "--curve", long_curve,
			     "--json", NULL };
	char *hyst[] = { "stray", "firmware-table", "--curve", CURVE,
			 "--hysteresis-deg", "20", "--json", NULL };
	char *unwritable[] = { "stray", "firmware-table", "--curve", CURVE,
			       "--out-bin", out, NULL };
	char *norm[] = { "stray", "firmware-table", "--curve", CURVE,
			 "--normalisation", "pixel", "--json", NULL };
	int i, k = 0;

	(void)state;
	snprintf(nan_curve, sizeof(nan_curve), "%s/nan.csv", dir);
	snprintf(long_curve, sizeof(long_curve), "%s/long.csv", dir);
	snprintf(out, sizeof(out), "%s/no/such/dir/t.bin", dir);
	write_file(nan_curve, "theta_deg,alpha\n0,1\n1,nan\n2,0.1\n");
	k = snprintf(text, sizeof(text), "theta_deg,alpha\n");
	for (i = 0; i < 200; i++)	/* more rows than the table holds */
		k += snprintf(text + k, sizeof(text) - k, "%g,%g\n", i * 0.4,
			      exp(-0.2 * i));
	write_file(long_curve, text);

	expect_error(no_curve, 2, "--curve is required");
	expect_error(missing, 2, "/nonexistent/c.csv");
	expect_error(nan_run, 2, "nan.csv");
	/* more rows than the table holds: thinned to them, the error said */
	{
		static struct cli_run lr;
		cJSON *o;

		assert_int_equal(run_stray(&lr, long_run), 0);
		o = cJSON_Parse(lr.out);
		assert_non_null(o);
		assert_near(json_num(o, "curve_rows"), 200, 0);
		assert_near(json_num(o, "n_curve"), 128, 0);
		assert_true(json_num(o, "thinned_max_log10_error") < 0.05);
		cJSON_Delete(o);
	}
	expect_error(hyst, 2, "hysteresis_deg");
	expect_error(unwritable, 1, "t.bin");
	expect_error(norm, 2, "'pixel' is not consistent or thesis");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_help),
		cmocka_unit_test(test_blob_and_c_source),
		cmocka_unit_test(test_json_summary),
		cmocka_unit_test(test_normalisation),
		cmocka_unit_test(test_orbit_normalisation),
		cmocka_unit_test(test_bad_input),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
