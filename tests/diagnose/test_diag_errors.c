/*
 * test_diag_errors.c - bad input to `stray diagnose` gets one stderr line
 * naming the file, field or value, and exit status 2; never a crash.
 * Fast (no tracing happens before the input is checked): runs under the
 * sanitizers too.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tools/run_cli.h"

static struct cli_run r;

/* Write text to a temporary CSV; the path is returned in buf. */
static void write_csv(char *buf, const char *text)
{
	int fd;
	FILE *f;

	strcpy(buf, "/tmp/stray_diag_err_XXXXXX.csv");
	fd = mkstemps(buf, 4);
	assert_true(fd >= 0);
	f = fdopen(fd, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static void expect_bad(const char *text, const char *needle)
{
	char path[64];
	char *argv[] = { "stray", "diagnose", path, "--scene", "ref4", NULL };

	write_csv(path, text);
	run_stray(&r, argv);
	unlink(path);
	assert_int_equal(r.status, 2);
	assert_int_equal(r.err_lines, 1);
	if (!strstr(r.err, needle))
		fail_msg("stderr '%s' lacks '%s'", r.err, needle);
}

static void test_no_sigma_column(void **state)
{
	(void)state;
	expect_bad("theta_deg,alpha\n0,1\n10,0.9\n40,1e-5\n", "sigma");
}

static void test_non_positive_alpha(void **state)
{
	(void)state;
	expect_bad("theta_deg,alpha,sigma\n0,1,0.01\n10,0.9,0.01\n"
		   "40,0,1e-6\n", "alpha");
}

static void test_angle_out_of_range(void **state)
{
	(void)state;
	expect_bad("theta_deg,alpha,sigma\n0,1,0.01\n10,0.9,0.01\n"
		   "95,1e-5,1e-6\n", "theta_deg");
}

static void test_nan(void **state)
{
	(void)state;
	expect_bad("theta_deg,alpha,sigma\n0,1,0.01\n10,nan,0.01\n"
		   "40,1e-5,1e-6\n", "stray_diag_err_");
}

static void test_missing_file_and_usage(void **state)
{
	char *missing[] = { "stray", "diagnose", "/nonexistent/m.csv",
			    "--scene", "ref4", NULL };
	char *no_scene[] = { "stray", "diagnose", "m.csv", NULL };
	char *help[] = { "stray", "diagnose", "--help", NULL };

	(void)state;
	run_stray(&r, missing);
	assert_int_not_equal(r.status, 0);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "/nonexistent/m.csv"));
	run_stray(&r, no_scene);
	assert_int_equal(r.status, 2);
	assert_non_null(strstr(r.err, "--scene"));
	run_stray(&r, help);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "usage: stray diagnose"));
}

/* A bad --response or --spectrum: one line naming the file (and line),
 * exit 2, before any trace. */
static void test_bad_band(void **state)
{
	char good[64], bad[64];
	char *missing[] = { "stray", "diagnose", good, "--scene", "ref4",
			    "--response", "/nonexistent/r.csv", NULL };
	char *decreasing[] = { "stray", "diagnose", good, "--scene", "ref4",
			       "--spectrum", bad, NULL };
	char *zero[] = { "stray", "diagnose", good, "--scene", "ref4",
			 "--response", bad, NULL };

	(void)state;
	write_csv(good, "theta_deg,alpha,sigma\n0,1,0.01\n40,1e-5,1e-6\n");
	run_stray(&r, missing);
	assert_int_equal(r.status, 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "/nonexistent/r.csv"));
	write_csv(bad, "wavelength_nm,irradiance\n500,1\n400,1\n");
	run_stray(&r, decreasing);
	unlink(bad);
	assert_int_equal(r.status, 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "wavelength_nm"));
	write_csv(bad, "wavelength_nm,qe\n2000,0.5\n3000,0.5\n");
	run_stray(&r, zero);	/* no overlap with the Sun x it in band */
	unlink(bad);
	unlink(good);
	assert_int_equal(r.status, 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "stray_diag_err_"));
}

static void test_cause_list(void **state)
{
	static const char *const names[] = {
		"reflectance", "knife_edge_radius", "abg_scatter",
		"acceptance_cone", "angle_offset", "pivot_offset", "floor",
		"light_leak", "bevel_face", "scale", "spectral_slope",
		"beam_divergence", "beam_profile"
	};
	char *argv[] = { "stray", "diagnose", "--causes", NULL };
	size_t i;
	char key[64];

	(void)state;
	run_stray(&r, argv);
	assert_int_equal(r.status, 0);
	for (i = 0; i < sizeof(names) / sizeof(names[0]); i++) {
		snprintf(key, sizeof(key), "\n%s:", names[i]);
		if (!strstr(r.out, key) && strncmp(r.out, key + 1,
						    strlen(key + 1)) != 0)
			fail_msg("cause %s not listed", names[i]);
	}
}

/* --lens (system curves): a bad lens table is bad input, named. */
static void test_bad_lens(void **state)
{
	char path[64], lens[64];
	char *argv[] = { "stray", "diagnose", path, "--scene", "ref4",
			 "--lens", lens, "--rays", "2000", NULL };

	(void)state;
	write_csv(path, "theta_deg,alpha,sigma\n0,1,0.01\n10,0.9,0.01\n"
		  "40,1e-5,1e-6\n");
	write_csv(lens, "theta_deg,alpha\n0,1\n10,abc\n");
	run_stray(&r, argv);
	unlink(path);
	unlink(lens);
	assert_int_equal(r.status, 2);
	assert_int_equal(r.err_lines, 1);
	if (!strstr(r.err, lens) || !strstr(r.err, "abc"))
		fail_msg("stderr '%s' lacks the lens file or value", r.err);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_no_sigma_column),
		cmocka_unit_test(test_non_positive_alpha),
		cmocka_unit_test(test_angle_out_of_range),
		cmocka_unit_test(test_bad_lens),
		cmocka_unit_test(test_nan),
		cmocka_unit_test(test_missing_file_and_usage),
		cmocka_unit_test(test_bad_band),
		cmocka_unit_test(test_cause_list),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
