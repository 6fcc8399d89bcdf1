/*
 * test_diag_speed.c - issue 27's savings change no bit: a diagnosis with
 * the greedy step's candidates fitted by two threads (candidates.c) gives
 * the result of one thread, byte for byte, with the same traces, every
 * one made on the caller's thread (stray-mpi's farm is driven from one
 * thread); and the screen of a re-trace cause joining another one
 * (run.c) is reached and said.  Small traces (the library with a runner
 * of the test's own): runs under the sanitizers too.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "diagnose/diag_data.h"
#include "diagnose/diag_eval.h"
#include "diagnose/diag_result.h"
#include "tracer/runner.h"
#include "truth.h"

/* A runner that traces here and counts the calls made off the thread
 * that started the diagnosis. */
struct spy {
	pthread_t main;
	int calls, off_main;
};

static int spy_run(void *ctx, const struct tracer_scene_spec *spec,
		   const struct tracer_scene *s,
		   const struct tracer_trace_opts *o,
		   struct tracer_result *res, struct stray_error *err)
{
	struct spy *sp = ctx;

	sp->calls++;
	sp->off_main += !pthread_equal(pthread_self(), sp->main);
	return tracer_run(&tracer_runner_local, spec, s, o, res, err);
}

/* The log without its stage timings (wall and cpu seconds differ). */
static char logged[16384];

static void keep_line(const char *line)
{
	if (strchr(line, '[') || strlen(logged) + strlen(line) + 2 >
	    sizeof(logged))
		return;
	strcat(logged, line);
	strcat(logged, "\n");
}

static const double theta[] = { 0, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80 };
#define N_THETA (sizeof(theta) / sizeof(theta[0]))

struct outcome {
	double chi2_before, chi2_after, single_chi2[DIAG_CAUSES_MAX];
	double p[DIAG_FIT_PMAX];
	int n_named, n_tentative;
	size_t traces;
	char log[sizeof(logged)];
};

static void diagnose(const char *csv, int fit_threads, struct spy *sp,
		     struct outcome *out)
{
	const struct tracer_runner runner = { spy_run, sp, NULL };
	const struct diag_fit *f;
	struct stray_error err;
	struct diag_data d;
	struct diag_eval e;
	struct diag_result r;
	int i;

	stray_error_clear(&err);
	memset(out, 0, sizeof(*out));
	logged[0] = '\0';
	sp->main = pthread_self();
	assert_int_equal(diag_data_load(csv, &d, &err), STRAY_OK);
	diag_eval_init(&e, "ref4", d.theta_deg, d.n, &runner);
	e.n_paths = 6000;
	e.seed = 7;
	e.threads = 2;
	e.fit_threads = fit_threads;
	assert_int_equal(diag_eval_prepare(&e, &err), STRAY_OK);
	assert_int_equal(diag_run(&e, &d, &r, keep_line, &err), STRAY_OK);
	out->chi2_before = r.chi2_before;
	out->chi2_after = r.chi2_after;
	for (i = 0; i < r.n_single && i < DIAG_CAUSES_MAX; i++)
		out->single_chi2[i] = r.single[i].chi2;
	f = r.named.n_causes ? &r.named : &r.tentative;
	for (i = 0; i < f->n_p; i++)	/* the rest is not the fit's */
		out->p[i] = f->p[i];
	out->n_named = r.named.n_causes;
	out->n_tentative = r.tentative.n_causes;
	out->traces = e.n_traces;
	memcpy(out->log, logged, sizeof(out->log));
	diag_result_free(&r);
	diag_eval_free(&e);
	diag_data_free(&d);
}

static void test_two_threads_same_bits(void **state)
{
	static struct outcome one, two;
	struct truth_config c;
	struct spy s1 = { 0 }, s2 = { 0 };
	char csv[] = "/tmp/stray_diag_speed_XXXXXX.csv";
	int fd = mkstemps(csv, 4);

	(void)state;
	assert_true(fd >= 0);
	close(fd);
	/* a knife edge and a pivot offset hidden: both re-trace causes
	 * earn their place alone, so the one named first is joined by the
	 * other through the screen, and its combined grid is traced */
	truth_defaults(&c, theta, N_THETA);
	c.n_paths = 60000;
	c.sets[c.n_sets++] = "edge_radius=0.1";
	c.pivot_mm = 4.0;
	assert_int_equal(truth_write(&c, csv), 0);
	diagnose(csv, 1, &s1, &one);
	diagnose(csv, 0, &s2, &two);
	unlink(csv);
	fprintf(stderr, "%s", two.log);
	assert_true(one.n_named + one.n_tentative >= 1);
	assert_int_equal(one.traces, two.traces);
	assert_int_equal(s1.calls, s2.calls);
	assert_int_equal(s1.off_main, 0);
	assert_int_equal(s2.off_main, 0);	/* traces: the caller's */
	assert_memory_equal(&one, &two, sizeof(one));
	/* the screen was reached, and a cause that passed it entered on
	 * its traced combined grid */
	assert_non_null(strstr(two.log, "with the interaction neglected"));
	assert_non_null(strstr(two.log, "+ knife_edge_radius"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_threads_same_bits),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
