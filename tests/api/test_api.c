/*
 * test_api.c - the commands as flat C calls (tools/api.h, issue 32): the
 * --json object and the error line of the command, the curve and frames
 * it hands over, the cancel flag stopping a long trace, and the curve
 * reader and writer.  Linked from the same objects as `stray` (and run
 * under ASan+UBSan in the second pass).
 */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "tools/api.h"

/* scratch files in a folder of their own (main) */
static char dir[] = "/tmp/test_api.XXXXXX";
static char path_c[64], path_bad[64];

static double now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void json_and_errors(void **state)
{
	struct stray_api_result *r;

	(void)state;
	assert_int_equal(stray_api_run("photometry", "{\"sensor\": \"st16-like\"}",
				       &r), 0);
	assert_non_null(strstr(stray_api_json(r), "\"sun\":"));
	assert_string_equal(stray_api_error(r), "");
	assert_string_equal(stray_api_command(r),
			    "stray --json photometry --sensor st16-like");
	stray_api_result_free(r);
	/* the CLI's one line, not printed: kept */
	assert_int_equal(stray_api_run("fdr", "{\"rate\": \"x\"}", &r), 2);
	assert_null(stray_api_json(r));
	assert_string_equal(stray_api_error(r), "stray fdr: option '--rate': "
			    "'x' is not a finite number (see 'stray fdr --help')");
	stray_api_result_free(r);
	assert_int_equal(stray_api_run("nosuch", NULL, &r), 2);
	assert_string_equal(stray_api_error(r), "stray: 'nosuch' is not a "
			    "stray command; see 'stray --help'");
	stray_api_result_free(r);
	assert_int_equal(stray_api_run("fdr", "[1]", &r), 2);
	assert_string_equal(stray_api_error(r),
			    "stray fdr: options are not a JSON object");
	stray_api_result_free(r);
	assert_int_equal(stray_api_run("fdr", "{\"rate\": {\"a\": 1}}", &r), 2);
	assert_non_null(strstr(stray_api_error(r), "option '--rate': not a"));
	stray_api_result_free(r);
	/* numbers, flags, repeated options */
	assert_int_equal(stray_api_run("fdr", "{\"rate\": 2.5, \"detector-noise\""
				       ": true, \"plot\": false}", &r), 0);
	assert_string_equal(stray_api_command(r), "stray --json fdr --rate 2.5 "
			    "--detector-noise");
	stray_api_result_free(r);
}

/* A note `stray` prints beside its result is kept, not printed: the Sun
 * not excluded within a curve that ends above alpha_required. */
static void notes_kept(void **state)
{
	struct stray_api_result *r;
	char path[96], opts[200];
	FILE *f;

	(void)state;
	snprintf(path, sizeof(path), "%s/flat.csv", dir);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs("theta_deg,alpha\n0,1\n30,1e-3\n90,1e-3\n", f);
	fclose(f);
	snprintf(opts, sizeof(opts), "{\"curve\": \"%s\"}", path);
	assert_int_equal(stray_api_run("exclusion", opts, &r), 0);
	assert_string_equal(stray_api_error(r), "");
	assert_non_null(strstr(stray_api_notes(r), "stray exclusion: "));
	assert_non_null(strstr(stray_api_notes(r), "flat.csv: sun not "
			       "excluded within the curve"));
	assert_int_equal(strchr(stray_api_notes(r), '\n')[1], '\0');
	stray_api_result_free(r);
	assert_int_equal(stray_api_run("photometry", NULL, &r), 0);
	assert_string_equal(stray_api_notes(r), "");
	stray_api_result_free(r);
}

static void trace_curve_and_frames(void **state)
{
	struct stray_api_result *r;
	const char *want[] = { "theta_deg", "alpha", "sigma", "direct",
			       "order1", "order2", "order3plus" };
	size_t k, n;
	int rows, cols;
	uint16_t *f;

	(void)state;
	assert_int_equal(stray_api_run("trace", "{\"scene\": \"ref4\", \"angles\""
		": \"0:20:10\", \"rays\": 4000, \"threads\": 1, \"set\": "
		"[\"reflectance=0.08\"]}", &r), 0);
	assert_int_equal(stray_api_curve_rows(r), 3);
	assert_int_equal(stray_api_curve_columns(r), 7);
	for (k = 0; k < 7; k++)
		assert_string_equal(stray_api_curve_name(r, k), want[k]);
	assert_null(stray_api_curve_name(r, 7));
	assert_true(stray_api_curve_column(r, 1)[0] == 1.0);
	assert_true(stray_api_curve_column(r, 0)[2] == 20.0);
	assert_true(stray_api_curve_n_meta(r) >= 3);
	assert_non_null(strstr(stray_api_json(r), "\"worst_rel_sigma\""));
	assert_null(stray_api_frames_take(r, &n, &rows, &cols));
	/* the writer and the reader of the commands */
	{
		const char *names[3] = { "theta_deg", "alpha", "sigma" };
		const double *c3[3] = { stray_api_curve_column(r, 0),
			stray_api_curve_column(r, 1), stray_api_curve_column(r, 2) };
		const char *meta[1] = { stray_api_curve_meta(r, 0) };
		struct stray_api_result *w, *rd;

		assert_int_equal(stray_api_curve_write(path_c, "a command",
			3, 3, names, c3, 1, meta, &w), 0);
		assert_int_equal(stray_api_curve_read(path_c, &rd), 0);
		assert_int_equal(stray_api_curve_rows(rd), 3);
		assert_int_equal(stray_api_curve_columns(rd), 3);
		assert_string_equal(stray_api_curve_meta(rd, 0), " command: a command");
		stray_api_result_free(w);
		stray_api_result_free(rd);
		unlink(path_c);
	}
	stray_api_result_free(r);
	assert_int_equal(stray_api_run("frames", "{\"alpha\": 1e-6, \"frames\": 2,"
				       " \"window\": 32, \"seed\": 7}", &r), 0);
	f = stray_api_frames_take(r, &n, &rows, &cols);
	assert_non_null(f);
	assert_int_equal(n, 2);
	assert_int_equal(rows, 32);
	assert_int_equal(cols, 32);
	assert_null(stray_api_frames_take(r, &n, &rows, &cols));
	stray_api_result_free(r);	/* the frames are the caller's now */
	assert_true(f[0] > 0 || f[1] > 0);
	stray_api_free(f);
}

static void bad_curve_file(void **state)
{
	struct stray_api_result *r;
	FILE *fp = fopen(path_bad, "w");

	(void)state;
	fputs("theta_deg,alpha\n0,1\n5,nan\n", fp);
	fclose(fp);
	assert_int_equal(stray_api_curve_read(path_bad, &r), 2);
	assert_non_null(strstr(stray_api_error(r), "api_bad.csv:3"));
	assert_non_null(strstr(stray_api_error(r), dir));
	assert_int_equal(stray_api_curve_rows(r), 0);
	stray_api_result_free(r);
	unlink(path_bad);
}

struct long_call { int rc; char err[256]; };

static void *long_trace(void *arg)
{
	struct long_call *c = arg;
	struct stray_api_result *r;

	c->rc = stray_api_run("trace", "{\"scene\": \"ref4\", \"angles\": "
			      "\"0:90:1\", \"rays\": 500000000, \"threads\": 2}",
			      &r);
	snprintf(c->err, sizeof(c->err), "%s", stray_api_error(r));
	stray_api_result_free(r);
	return NULL;
}

static void cancel_stops_a_trace(void **state)
{
	struct long_call c = { -1, "" };
	struct stray_api_result *r;
	pthread_t t;
	double t0;

	(void)state;
	assert_int_equal(pthread_create(&t, NULL, long_trace, &c), 0);
	nanosleep(&(struct timespec){ 0, 300000000L }, NULL);
	t0 = now();
	stray_api_cancel(1);
	pthread_join(t, NULL);
	assert_true(now() - t0 < 1.0);
	assert_int_equal(c.rc, 1);
	assert_string_equal(c.err, "stray trace: trace: interrupted");
	/* the next call clears the flag */
	assert_int_equal(stray_api_run("trace", "{\"scene\": \"ref4\", \"angles\""
				       ": \"0:10:5\", \"rays\": 2000}", &r), 0);
	stray_api_result_free(r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(json_and_errors),
		cmocka_unit_test(notes_kept),
		cmocka_unit_test(trace_curve_and_frames),
		cmocka_unit_test(bad_curve_file),
		cmocka_unit_test(cancel_stops_a_trace),
	};

	int rc;

	if (!mkdtemp(dir))
		return 1;
	snprintf(path_c, sizeof(path_c), "%s/api_c.csv", dir);
	snprintf(path_bad, sizeof(path_bad), "%s/api_bad.csv", dir);
	rc = cmocka_run_group_tests(tests, NULL, NULL);
	rmdir(dir);
	return rc;
}
