/*
 * test_io.c - the hosted readers (table.c, curve_io.c, spectrum_io.c,
 * sensor_io.c): good files round-trip; every bad file is refused with one
 * message naming the file, line and column or key.
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
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/provenance.h"
#include "stray/sensor_io.h"
#include "stray/spectrum_io.h"
#include "stray/table.h"

static char msg[1024];

/* Parse text as a curve; return the status and leave the message in msg. */
static int curve_text(const char *text, struct stray_curve *c)
{
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_curve_parse("c.csv", text, strlen(text), c, &err);
	stray_error_format(&err, msg, sizeof(msg));
	return rc;
}

static void expect_curve_error(const char *text, const char *needle)
{
	struct stray_curve c;

	assert_int_equal(curve_text(text, &c), STRAY_EPARSE);
	if (!strstr(msg, needle))
		fail_msg("message '%s' lacks '%s'", msg, needle);
	assert_null(strchr(msg, '\n'));
}

static void test_curve_parse_good_file(void **state)
{
	struct stray_curve c;

	(void)state;
	assert_int_equal(curve_text("# kind: baffle\r\n# source: lab\n"
		"theta_deg,alpha,sigma,order1\n0,1,0.01,0.5\n\n"
		"\"1\", 0.97 ,0.01,0.4\n", &c), STRAY_OK);
	assert_int_equal(c.n, 2);
	assert_near(c.alpha[1], 0.97, 0.0);
	assert_non_null(c.sigma);
	assert_int_equal(c.n_extra, 1);
	assert_string_equal(c.extra_name[0], "order1");
	assert_int_equal(c.n_meta, 2);
	stray_curve_free(&c);
}

/* docs/formats.md: an empty or nan cell is an error with the line number. */
static void test_curve_parse_bad_cells(void **state)
{
	(void)state;
	expect_curve_error("theta_deg,alpha\n0,1\n5,nan\n",
			   "c.csv:3: alpha 'nan': is not a finite number");
	expect_curve_error("theta_deg,alpha\n0,1\n5,\n", "c.csv:3: alpha");
	expect_curve_error("theta_deg,alpha\n0,1\n5,0.1x\n", "'0.1x'");
	expect_curve_error("theta_deg,alpha\n0,1\n5,-0.1\n", "c.csv:3: alpha");
	expect_curve_error("theta_deg,alpha\n0,1\n0,0.5\n",
			   "c.csv:3: theta_deg: angles must be strictly increasing");
	expect_curve_error("theta_deg,alpha\n0,1,3\n", "c.csv:2: row");
	expect_curve_error("theta,alpha\n0,1\n", "theta_deg");
	expect_curve_error("theta_deg,alpha\n", "no rows");
	expect_curve_error("# only a comment\n", "no header");
	expect_curve_error("theta_deg,alpha\n0,\"1\n", "c.csv:2");
	expect_curve_error("theta_deg,alpha,alpha\n0,1,1\n", "duplicate");
}

static void test_curve_save_load_round_trip(void **state)
{
	char path[] = "/tmp/stray_curve_XXXXXX";
	double order[3] = { 0.1, 0.2, 0.3 };
	struct stray_curve c, d;
	struct stray_error err;
	int fd = mkstemp(path), i;

	(void)state;
	assert_true(fd >= 0);
	close(fd);
	stray_error_clear(&err);
	assert_int_equal(stray_curve_alloc(&c, 3, 1, &err), STRAY_OK);
	for (i = 0; i < 3; i++) {
		c.theta_deg[i] = 10.0 * i;
		c.alpha[i] = pow(10.0, -3.0 * i);	/* alpha(0) = 1 */
		c.sigma[i] = 0.01 * c.alpha[i];
	}
	assert_int_equal(stray_curve_add_column(&c, "order1", order, &err), 0);
	assert_int_equal(stray_curve_add_meta(&c, "kind", "system", &err), 0);
	assert_int_equal(stray_curve_save(path, &c, &err), STRAY_OK);
	assert_int_equal(stray_curve_load(path, &d, &err), STRAY_OK);
	for (i = 0; i < 3; i++)
		assert_rel(d.alpha[i], c.alpha[i], 1e-9);
	assert_string_equal(d.extra_name[0], "order1");
	assert_near(d.extra[0][2], 0.3, 1e-12);
	assert_int_equal(d.n_meta, 2);	/* the version, then ours */
	{
		struct stray_table t = { 0 };

		t.meta = d.meta;
		t.n_meta = d.n_meta;
		assert_string_equal(stray_table_meta(&t, "kind"), "system");
		assert_non_null(strstr(stray_table_meta(&t, "version"),
				       "stray " STRAY_VERSION " (git "));
	}
	stray_curve_free(&c);
	stray_curve_free(&d);
	unlink(path);
}

/* A save that cannot complete leaves the old file untouched. */
static void test_curve_save_failure_keeps_old_file(void **state)
{
	struct stray_curve c;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_curve_alloc(&c, 1, 0, &err), STRAY_OK);
	c.alpha[0] = 1.0;
	assert_int_equal(stray_curve_save("/nonexistent-dir/c.csv", &c, &err),
			 STRAY_EIO);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, "/nonexistent-dir/c.csv"));
	stray_curve_free(&c);
}

static int spectrum_text(const char *text)
{
	char path[] = "/tmp/stray_spec_XXXXXX";
	struct stray_spectrum_data d;
	struct stray_error err;
	int fd = mkstemp(path), rc;
	FILE *f = fdopen(fd, "w");

	fputs(text, f);
	fclose(f);
	stray_error_clear(&err);
	rc = stray_spectrum_load(path, &d, &err);
	stray_error_format(&err, msg, sizeof(msg));
	if (rc == STRAY_OK)
		stray_spectrum_data_free(&d);
	unlink(path);
	return rc;
}

static void test_spectrum_bad_files(void **state)
{
	(void)state;
	assert_int_equal(spectrum_text("wavelength_nm,qe\n400,0.1\n500,0.3\n"),
			 STRAY_OK);
	assert_int_equal(spectrum_text("wavelength_nm,qe\n400,0.1\n399,0.3\n"),
			 STRAY_EPARSE);
	assert_non_null(strstr(msg, ":3: wavelength_nm"));
	assert_int_equal(spectrum_text("wavelength_nm,qe\n400,0.1\n500,-0.3\n"),
			 STRAY_EPARSE);
	assert_non_null(strstr(msg, ":3: qe"));
	assert_int_equal(spectrum_text("wavelength_nm,qe\n400,NaN\n500,0.3\n"),
			 STRAY_EPARSE);
	assert_non_null(strstr(msg, ":2: qe 'NaN'"));
	assert_int_equal(spectrum_text("lambda,qe\n400,0.1\n500,0.3\n"),
			 STRAY_EPARSE);
	assert_int_equal(spectrum_text("wavelength_nm,qe\n400,0.1\n"),
			 STRAY_EPARSE);
	assert_non_null(strstr(msg, "at least 2 rows"));
}

/* A binary file is refused as such, not parsed up to its first NUL. */
static void test_table_rejects_nul_bytes(void **state)
{
	static const char text[] = "a,b\n1,2\n\0\x01\x02";
	struct stray_table t;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_table_parse("bin.csv", text, sizeof(text) - 1,
					   &t, &err), STRAY_EPARSE);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, "bin.csv: file: contains a NUL byte"));
}

static void test_builtin_spectra_all_load(void **state)
{
	const struct stray_builtin_spectrum *b;
	struct stray_spectrum_data d;
	struct stray_error err;
	char name[128];
	size_t n, i;

	(void)state;
	b = stray_builtin_spectra(&n);
	assert_int_equal(n, 5);
	for (i = 0; i < n; i++) {
		snprintf(name, sizeof(name), "builtin:%s", b[i].name);
		stray_error_clear(&err);
		assert_int_equal(stray_spectrum_load(name, &d, &err), STRAY_OK);
		assert_true(d.s.n > 20);
		stray_spectrum_data_free(&d);
	}
	stray_error_clear(&err);
	assert_int_equal(stray_spectrum_load("builtin:nope", &d, &err),
			 STRAY_ENOTFOUND);
	assert_int_equal(stray_spectrum_load("/no/such/file.csv", &d, &err),
			 STRAY_ENOTFOUND);
	assert_int_equal(err.code, STRAY_ENOTFOUND);	/* first error wins */
}

static int sensor_text(const char *json, struct stray_sensor *s)
{
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_sensor_parse("s.json", json, "/data", s, &err);
	stray_error_format(&err, msg, sizeof(msg));
	return rc;
}

static void test_sensor_json(void **state)
{
	struct stray_sensor s;

	(void)state;
	assert_int_equal(sensor_text("{\"name\":\"wide\",\"t_exp_s\":0.2,"
		"\"qe\":\"qe.csv\",\"sun\":\"builtin:sun_am0_astm_g173_etr\"}", &s),
		STRAY_OK);
	assert_string_equal(s.name, "wide");
	assert_near(s.t_exp_s, 0.2, 0.0);
	assert_near(s.pixels_x, 2592.0, 0.0);	/* st16-like default kept */
	assert_string_equal(s.qe, "/data/qe.csv");
	assert_string_equal(s.sun, "builtin:sun_am0_astm_g173_etr");

	assert_int_equal(sensor_text("{\"t_exposure\":0.2}", &s), STRAY_ENOTFOUND);
	assert_string_equal(msg, "s.json: sensor key 't_exposure': unknown (see docs/formats.md)");
	assert_int_equal(sensor_text("{\"t_exp_s\":\"fast\"}", &s), STRAY_EINVAL);
	assert_non_null(strstr(msg, "t_exp_s"));
	assert_int_equal(sensor_text("{\"pr_drs\":1.5}", &s), STRAY_EINVAL);
	assert_non_null(strstr(msg, "s.json: pr_drs 1.5"));
	assert_int_equal(sensor_text("{\"t_exp_s\":0.2,", &s), STRAY_EPARSE);
	assert_int_equal(sensor_text("[1,2]", &s), STRAY_EPARSE);
}

static void test_sensor_load_by_name(void **state)
{
	struct stray_sensor s;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_sensor_load("st16-like", &s, &err), STRAY_OK);
	assert_near(s.star_window_px, 113.0, 0.0);
	assert_int_equal(stray_sensor_load("st17", &s, &err), STRAY_ENOTFOUND);
	stray_error_format(&err, msg, sizeof(msg));
	assert_non_null(strstr(msg, "'st17'"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_curve_parse_good_file),
		cmocka_unit_test(test_curve_parse_bad_cells),
		cmocka_unit_test(test_curve_save_load_round_trip),
		cmocka_unit_test(test_curve_save_failure_keeps_old_file),
		cmocka_unit_test(test_spectrum_bad_files),
		cmocka_unit_test(test_table_rejects_nul_bytes),
		cmocka_unit_test(test_builtin_spectra_all_load),
		cmocka_unit_test(test_sensor_json),
		cmocka_unit_test(test_sensor_load_by_name),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
