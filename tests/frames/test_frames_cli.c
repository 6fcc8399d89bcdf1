/*
 * test_frames_cli.c - `stray frames` as a user runs it: the JSON keys of
 * issue 13, the thesis normalisation (k_px = 1) against the consistent
 * one, FITS output, and bad input (one stderr line naming the value,
 * exit 2).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cJSON.h>
#include <cmocka.h>
#include <math.h>

#include "tools/run_cli.h"

#define STRAY(r, ...) run_stray(r, (char *[]){ "stray", __VA_ARGS__, NULL })

static struct cli_run r;

static double key(const cJSON *o, const char *k)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);

	if (!cJSON_IsNumber(v))
		fail_msg("JSON key '%s' missing or not a number", k);
	return v->valuedouble;
}

static void test_frames_json_keys(void **state)
{
	static const char *const keys[] = { "theta_deg", "frames",
		"false_stars_per_image", "false_stars_sigma", "model_fdr",
		"model_fdr_extended", "k_px" };
	cJSON *o;
	size_t i;

	(void)state;
	assert_int_equal(STRAY(&r, "frames", "--alpha", "3e-7", "--window",
			       "128", "--frames", "2", "--json"), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	for (i = 1; i < sizeof(keys) / sizeof(keys[0]); i++)
		(void)key(o, keys[i]);
	assert_string_equal(cJSON_GetObjectItem(o, "normalisation")->valuestring,
			    "consistent");
	assert_string_equal(cJSON_GetObjectItem(o, "detector")->valuestring,
			    "thesis");
	/* k_px = A_cs / (n_px A_px) = 132.7 mm^2 / 24.4 mm^2 (issue 13) */
	assert_true(fabs(key(o, "k_px") - 5.44) < 0.01);
	assert_true(key(o, "model_fdr_extended") > key(o, "model_fdr"));
	{	/* the real detector needs less light than eq. 2.18 says,
		 * which needs less than the thesis's k_px = 1 */
		const cJSON *a = cJSON_GetObjectItem(o, "alpha_required");

		assert_non_null(a);
		assert_true(key(a, "extended") < key(a, "model"));
		assert_true(key(a, "model") < key(a, "thesis_k1"));
		assert_true(fabs(key(a, "thesis_k1") / 1.92e-6 - 1) < 0.01);
	}
	cJSON_Delete(o);
}

/* alpha from the curve at theta (log-linear, as `stray exclusion`). */
static void test_frames_curve_theta(void **state)
{
	cJSON *o;

	(void)state;
	assert_int_equal(STRAY(&r, "frames", "--curve",
			       "examples/ref4_baffle_mitsuba.csv", "--theta", "40",
			       "--window", "64", "--json"), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	assert_true(key(o, "theta_deg") == 40.0);
	assert_true(key(o, "alpha") > 0.0 && key(o, "alpha") < 1.0);
	cJSON_Delete(o);
}

/* The same pixel level under both normalisations: alpha x k_px. */
static void test_frames_normalisations_agree(void **state)
{
	cJSON *a, *b;

	(void)state;
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
			       "--json"), 0);
	a = cJSON_Parse(r.out);
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
			       "--normalisation", "thesis", "--json"), 0);
	b = cJSON_Parse(r.out);
	assert_non_null(a);
	assert_non_null(b);
	assert_true(key(b, "k_px") == 1.0);
	assert_true(fabs(key(a, "stray_e_per_px") /
			 key(b, "stray_e_per_px") - key(a, "k_px")) < 1e-9);
	cJSON_Delete(a);
	cJSON_Delete(b);
}

static void test_frames_writes_fits(void **state)
{
	char dir[] = "/tmp/stray_frames_XXXXXX", path[256];
	FILE *f;
	char head[80];

	(void)state;
	assert_non_null(mkdtemp(dir));
	assert_int_equal(STRAY(&r, "frames", "--alpha", "1e-6", "--window", "64",
			       "--frames", "2", "--save", "1", "--out-dir", dir), 0);
	snprintf(path, sizeof(path), "%s/frame_000.fits", dir);
	f = fopen(path, "rb");
	assert_non_null(f);
	assert_int_equal(fread(head, 1, 80, f), 80);
	fclose(f);
	assert_memory_equal(head, "SIMPLE  =", 9);
	snprintf(path, sizeof(path), "%s/frame_001.fits", dir);
	assert_null(fopen(path, "rb"));		/* --save 1 */
	snprintf(path, sizeof(path), "%s/frame_000.fits", dir);
	unlink(path);
	rmdir(dir);
}

static void expect_bad(const char *needle)
{
	if (r.status != 2 || r.err_lines != 1 || !strstr(r.err, needle))
		fail_msg("exit %d, %d lines: '%s' (want 2, 1 line with '%s')",
			 r.status, r.err_lines, r.err, needle);
}

static void test_frames_bad_input(void **state)
{
	(void)state;
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv",
	      "--theta", "abc");
	expect_bad("theta");
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv",
	      "--theta", "nan");
	expect_bad("theta");
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv",
	      "--theta", "200");
	expect_bad("200");
	STRAY(&r, "frames", "--curve", "/nonexistent/curve.csv", "--theta", "30");
	expect_bad("/nonexistent/curve.csv");
	STRAY(&r, "frames", "--curve", "examples/ref4_baffle_mitsuba.csv");
	expect_bad("--theta");
	STRAY(&r, "frames", "--alpha", "1e-6", "--detector", "fancy");
	expect_bad("fancy");
	STRAY(&r, "frames", "--alpha", "1e-6", "--map", "/nonexistent/map.fits");
	expect_bad("/nonexistent/map.fits");
	STRAY(&r, "frames", "--alpha", "-1");
	expect_bad("alpha");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_frames_json_keys),
		cmocka_unit_test(test_frames_curve_theta),
		cmocka_unit_test(test_frames_normalisations_agree),
		cmocka_unit_test(test_frames_writes_fits),
		cmocka_unit_test(test_frames_bad_input),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
