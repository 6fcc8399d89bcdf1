/*
 * test_diag_surfaces.c - the surface at fault (issue 17 item 4): one
 * surface group's reflectance changed in the truth (vane 3's bevel face
 * x3), the analysis told nothing; re-weighting the recorded path table
 * per group must name that group, with the factor 3 inside its interval,
 * the written model must be a scene file that traces, and its re-trace
 * must confirm the gain.  A truth with no change names no group.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cJSON.h>

#include "tools/run_cli.h"
#include "diagnose/diag_data.h"
#include "diagnose/diag_eval.h"
#include "diagnose/diag_surfaces.h"
#include "stray/errfmt.h"
#include "tracer/runner.h"
#include "truth.h"

static const double theta[] = {
	0, 5, 10, 15, 20, 22, 24, 26, 28, 30, 35, 40, 45, 50, 55, 60, 70, 80
};
#define N (sizeof(theta) / sizeof(theta[0]))

/* Truth -> file -> localisation (and model + re-trace when model). */
static void localise(const struct truth_config *c, struct diag_surfaces *s,
		     const char *model)
{
	char path[] = "/tmp/stray_surf_XXXXXX.csv";
	int fd = mkstemps(path, 4);
	struct stray_error err;
	struct diag_data d;
	struct diag_eval e;
	struct diag_surf_table *t = NULL;

	assert_true(fd >= 0);
	close(fd);
	assert_int_equal(truth_write(c, path), 0);
	stray_error_clear(&err);
	assert_int_equal(diag_data_load(path, &d, &err), 0);
	unlink(path);
	diag_eval_init(&e, "ref4", d.theta_deg, d.n, &tracer_runner_local);
	e.n_paths = 200000;
	e.threads = 2;
	assert_int_equal(diag_surf_table_trace(&e, &t, &err), 0);
	assert_int_equal(diag_surfaces_fit(t, &d, s, &err), 0);
	if (model) {
		assert_int_equal(diag_surfaces_write_model(&e, s, model, &err),
				 0);
		if (diag_surfaces_confirm(&e, &d, s, &err))
			fail_msg("re-trace of %s: %s (%s)", model,
				 err.reason ? err.reason : "",
				 err.field ? err.field : "");
	}
	diag_surf_table_free(t);
	diag_eval_free(&e);
	diag_data_free(&d);
}

static void test_vane3_bevel_x3(void **state)
{
	struct truth_config c;
	struct diag_surfaces s;
	char model[] = "/tmp/stray_surf_model_XXXXXX.json";
	char obj[sizeof(model)];
	double f, lo, hi;
	int fd = mkstemps(model, 5);

	(void)state;
	assert_true(fd >= 0);
	close(fd);
	truth_defaults(&c, theta, N);
	c.group = "vane3_bevel";
	c.group_factor = 3.0;
	localise(&c, &s, model);
	printf("%d candidate groups, %d named\n", s.n_cand, s.n_named);
	assert_true(s.n_cand >= 10);
	assert_true(s.n_named >= 1);
	f = pow(10.0, s.log10_f[0]);
	lo = pow(10.0, s.ci_lo[0]);
	hi = pow(10.0, s.ci_hi[0]);
	printf("named %s x%.3f [%.3f, %.3f] of %d groups; rms %.4f -> %.4f, "
	       "re-trace %.4f; chi2 %.1f -> %.1f (n %d); fit %.3f s\n",
	       s.name[s.named[0]], f, lo, hi, s.n_cand, s.rms_before,
	       s.rms_after, s.rms_retrace, s.chi2_before, s.chi2_after,
	       s.n_fit, s.fit_seconds);
	assert_string_equal(s.name[s.named[0]], "vane3_bevel");
	assert_true(lo <= 3.0 && 3.0 <= hi);
	assert_true(hi / lo < 3.0);	/* an interval that says something */
	assert_true(s.rms_after < 0.5 * s.rms_before);
	assert_true(isfinite(s.rms_retrace));
	assert_true(s.rms_retrace < 0.5 * s.rms_before);
	snprintf(obj, sizeof(obj), "%.*s.obj", (int)(strlen(model) - 5), model);
	unlink(model);
	unlink(obj);
}

static void test_nothing_changed(void **state)
{
	struct truth_config c;
	struct diag_surfaces s;

	(void)state;
	truth_defaults(&c, theta, N);
	localise(&c, &s, NULL);
	printf("no change: %d named, chi2 %.1f (n %d)\n", s.n_named,
	       s.chi2_before, s.n_fit);
	assert_int_equal(s.n_named, 0);
}

/* As a user: `stray diagnose --surfaces --write-model M.json --json`, then
 * `stray trace --scene M.json` traces the written model. */
static void test_cli_write_model(void **state)
{
	static struct cli_run r;
	char path[] = "/tmp/stray_surf_cli_XXXXXX.csv";
	char dir[] = "/tmp/stray_surf_dir_XXXXXX", model[64], obj[64], out[64];
	struct truth_config c;
	char *diag[] = { "stray", "diagnose", path, "--scene", "ref4",
			 "--rays", "100000", "--threads", "2", "--surfaces",
			 "--write-model", model, "--json", NULL };
	char *trace[] = { "stray", "trace", "--scene", model, "--angles",
			  "0,30,60", "--rays", "5000", "--out", out, NULL };
	const cJSON *g;
	cJSON *j;
	int fd = mkstemps(path, 4);

	(void)state;
	assert_true(fd >= 0 && mkdtemp(dir) != NULL);
	close(fd);
	snprintf(model, sizeof(model), "%s/M.json", dir);
	snprintf(obj, sizeof(obj), "%s/M.obj", dir);
	snprintf(out, sizeof(out), "%s/c.csv", dir);
	truth_defaults(&c, theta, N);
	c.group = "vane3_bevel";
	c.group_factor = 3.0;
	assert_int_equal(truth_write(&c, path), 0);
	run_stray(&r, diag);
	unlink(path);
	if (r.status != 0)
		fprintf(stderr, "stray diagnose: %s\n", r.err);
	assert_int_equal(r.status, 0);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	g = cJSON_GetArrayItem(cJSON_GetObjectItem(cJSON_GetObjectItem(j,
		"surfaces"), "groups"), 0);
	assert_non_null(g);
	printf("cli: %s x%.3f, re-traced rms %.4f\n",
	       cJSON_GetObjectItem(g, "group")->valuestring,
	       cJSON_GetObjectItem(g, "factor")->valuedouble,
	       cJSON_GetObjectItem(cJSON_GetObjectItem(j, "surfaces"),
				   "rms_retrace")->valuedouble);
	assert_string_equal(cJSON_GetObjectItem(g, "group")->valuestring,
			    "vane3_bevel");
	cJSON_Delete(j);
	run_stray(&r, trace);
	if (r.status != 0)
		fprintf(stderr, "stray trace: %s\n", r.err);
	assert_int_equal(r.status, 0);
	unlink(model);
	unlink(obj);
	unlink(out);
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_vane3_bevel_x3),
		cmocka_unit_test(test_nothing_changed),
		cmocka_unit_test(test_cli_write_model),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
