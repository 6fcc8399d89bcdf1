/*
 * test_diag_runner.c - the diagnose library through its public headers
 * alone, with a runner of the test's own (tracer/runner.h): every trace
 * the evaluator makes goes through the runner it was given, with the
 * scene description other ranks would rebuild from (the causes' edits
 * after loading included), and a runner's failure is the evaluator's.
 * Small traces: runs under the sanitizers too.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "diagnose/diag_eval.h"
#include "stray/errfmt.h"
#include "tracer/runner.h"

/* A runner that counts, remembers what it was asked, and traces here
 * (or fails, when told to). */
struct spy {
	int calls, fail;
	char scene[32];
	double max_abg_g;
	int record_paths;
};

static int spy_run(void *ctx, const struct tracer_scene_spec *spec,
		   const struct tracer_scene *s,
		   const struct tracer_trace_opts *o,
		   struct tracer_result *res, struct stray_error *err)
{
	struct spy *sp = ctx;

	sp->calls++;
	snprintf(sp->scene, sizeof(sp->scene), "%s", spec->scene);
	sp->max_abg_g = fmax(sp->max_abg_g, spec->abg_g);
	sp->record_paths = o->record_paths;
	if (sp->fail)
		return stray_error_set(err, STRAY_EIO, "spy",
				       "this runner is down");
	return tracer_run(&tracer_runner_local, spec, s, o, res, err);
}

static const double theta[] = { 0.0, 10.0, 25.0, 45.0 };

static void eval_init(struct diag_eval *e, const struct tracer_runner *r)
{
	diag_eval_init(e, "ref4", theta, sizeof(theta) / sizeof(theta[0]), r);
	e->n_paths = 4000;
	e->seed = 3;
}

static void test_every_trace_through_the_runner(void **state)
{
	struct spy sp = { 0 };
	const struct tracer_runner runner = { spy_run, &sp, NULL };
	const struct diag_cause *abg = diag_cause_find("abg_scatter");
	struct diag_eval e;
	struct diag_state st;
	struct stray_error err;
	double alpha[4], sigma[4], g = 2.0;
	size_t i;

	(void)state;
	assert_non_null(abg);
	stray_error_clear(&err);
	eval_init(&e, &runner);
	assert_int_equal(diag_eval_prepare(&e, &err), STRAY_OK);
	assert_true(sp.calls >= 1);
	assert_int_equal((size_t)sp.calls, e.n_traces);
	assert_string_equal(sp.scene, "ref4");
	assert_true(sp.record_paths);	/* re-weighting needs the paths */
	assert_true(sp.max_abg_g == 0.0);	/* nominal: no lobe */

	diag_state_nominal(&st);
	abg->apply(&g, &st);		/* a re-traced cause */
	assert_int_equal(diag_eval_model(&e, &st, alpha, sigma, NULL, &err),
			 STRAY_OK);
	assert_int_equal((size_t)sp.calls, e.n_traces);
	assert_true(sp.calls >= 2);
	assert_true(sp.max_abg_g == g);	/* the edit travels in the spec */
	for (i = 0; i < 4; i++)
		assert_true(alpha[i] > 0.0 && sigma[i] >= 0.0 &&
			    isfinite(alpha[i]));
	diag_eval_free(&e);
}

static void test_same_curve_as_the_local_runner(void **state)
{
	struct spy sp = { 0 };
	const struct tracer_runner runner = { spy_run, &sp, NULL };
	struct diag_eval a, b;
	struct diag_state st;
	struct stray_error err;
	double al[4], sl[4], as[4], ss[4];

	(void)state;
	stray_error_clear(&err);
	eval_init(&a, &tracer_runner_local);
	eval_init(&b, &runner);
	diag_state_nominal(&st);
	assert_int_equal(diag_eval_prepare(&a, &err), STRAY_OK);
	assert_int_equal(diag_eval_prepare(&b, &err), STRAY_OK);
	assert_int_equal(diag_eval_model(&a, &st, al, sl, NULL, &err), 0);
	assert_int_equal(diag_eval_model(&b, &st, as, ss, NULL, &err), 0);
	assert_memory_equal(al, as, sizeof(al));
	assert_memory_equal(sl, ss, sizeof(sl));
	assert_true(sp.calls >= 1);
	diag_eval_free(&a);
	diag_eval_free(&b);
}

static void test_runner_failure_is_the_evaluators(void **state)
{
	struct spy sp = { 0 };
	const struct tracer_runner runner = { spy_run, &sp, NULL };
	struct diag_eval e;
	struct stray_error err;
	char line[256];

	(void)state;
	sp.fail = 1;
	stray_error_clear(&err);
	eval_init(&e, &runner);
	assert_int_equal(diag_eval_prepare(&e, &err), STRAY_EIO);
	assert_int_equal(sp.calls, 1);
	assert_int_equal(e.n_traces, 0);
	assert_non_null(strstr(stray_error_format(&err, line, sizeof(line)),
			       "this runner is down"));
	diag_eval_free(&e);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_trace_through_the_runner),
		cmocka_unit_test(test_same_curve_as_the_local_runner),
		cmocka_unit_test(test_runner_failure_is_the_evaluators),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
