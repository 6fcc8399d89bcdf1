/*
 * test_paths.c - path records (thesis §5.3): keys round-trip, the parts
 * add up to the scattered alpha, and re-weighting the recorded
 * alpha / prod(rho) with a new reflectance predicts a fresh trace at that
 * reflectance (what the diagnose fit relies on).
 */
#include <stdlib.h>
#include <string.h>

#include "tracer_test.h"
#include "tracer/baffle.h"
#include "tracer/path_report.h"

static void test_paths_keys_round_trip(void **state)
{
	const int g[9] = { 3, 0, 17, 63, 5, 6, 7, 8, 9 };
	int out[TRACER_SEQ_MAX];
	uint64_t k = tracer_seq_pack(g, 4);

	(void)state;
	assert_int_equal(tracer_seq_unpack(k, out), 4);
	assert_memory_equal(out, g, 4 * sizeof(int));
	assert_false(k & TRACER_SEQ_TRUNCATED);
	k = tracer_seq_pack(g, 9);
	assert_true(k & TRACER_SEQ_TRUNCATED);
	assert_int_equal(tracer_seq_unpack(k, out), TRACER_SEQ_MAX);
	assert_true(tracer_seq_pack(g, 2) != tracer_seq_pack(g + 1, 2));
}

static void trace_ref4(double rho, const double *th, size_t n,
		       struct tracer_scene *s, struct tracer_result *r)
{
	struct tracer_baffle b;
	struct tracer_trace_opts o;

	tracer_baffle_ref4(&b);
	b.segments = 128;
	b.reflectance = rho;
	tracer_scene_init(s);
	assert_int_equal(tracer_baffle_build(&b, s, NULL), 0);
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = n;
	o.n_paths = 60000;
	o.threads = 2;
	o.n_batches = 32;
	o.record_paths = 1;
	assert_int_equal(tracer_trace(s, &o, r, NULL), 0);
}

/* Sum over recorded paths of alpha_per_rho * prod(rho'(group)). */
static double reweighted(const struct tracer_result *r,
			 const struct tracer_scene *s, size_t j, double rho)
{
	double sum = 0.0;
	size_t i;

	for (i = 0; i < r->paths.cap; i++) {
		const struct tracer_path_entry *e = &r->paths.e[i];
		struct tracer_path_item it;

		if (!e->used || e->theta_index != j)
			continue;
		tracer_path_item_of(r, s, e, 0, &it);
		sum += it.geom * pow(rho, it.n_scatter);
	}
	return sum;
}

static void test_paths_add_up_and_reweight(void **state)
{
	const double th[] = { 0, 35, 60 };
	struct tracer_scene s4, s8;
	struct tracer_result r4, r8;
	size_t j;

	(void)state;
	trace_ref4(0.04, th, 3, &s4, &r4);
	trace_ref4(0.08, th, 3, &s8, &r8);
	for (j = 1; j < 3; j++) {
		double a, sg, d, sd, a8, s8v, d8, sd8;

		tracer_result_alpha(&r4, j, 0, -1, &a, &sg);
		tracer_result_alpha(&r4, j, 0, 0, &d, &sd);
		/* the parts are the scattered alpha, to rounding */
		assert_near(reweighted(&r4, &s4, j, 0.04), a - d, 1e-9 * a);
		tracer_result_alpha(&r8, j, 0, -1, &a8, &s8v);
		tracer_result_alpha(&r8, j, 0, 0, &d8, &sd8);
		/* alpha(0) moves too: normalise the prediction by it */
		assert_near(reweighted(&r4, &s4, j, 0.08) /
			    (1.0 + reweighted(&r4, &s4, 0, 0.08) -
			     reweighted(&r4, &s4, 0, 0.04)),
			    a8 - d8, 4.0 * hypot(2.2 * sg, s8v));
	}
	tracer_result_free(&r4);
	tracer_result_free(&r8);
	tracer_scene_free(&s4);
	tracer_scene_free(&s8);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_paths_keys_round_trip),
		cmocka_unit_test(test_paths_add_up_and_reweight),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
