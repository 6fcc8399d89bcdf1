/*
 * test_farm_set.c - the farm's one queue of pieces across a sweep's
 * traces (mpi/farm_set.h), without MPI: simulated ranks take pieces,
 * run them and hand the payloads back out of order; every trace comes
 * out with the bits of its own tracer_trace(), no main piece leaves
 * before its trace's guide, each rank is sent a trace's job and guide
 * once and before its pieces, and a rank stays on the traces whose
 * scene it built while they have pieces.
 */
#include <string.h>

#include "farm_set.h"
#include "tracer_test.h"
#include "tracer/scene_load.h"

#define N_TRACES 3
#define RANKS 3

static const char *const sets[N_TRACES][3] = {
	{ "segments=64", "arc_segments=2", "reflectance=0.04" },
	{ "segments=64", "arc_segments=2", "reflectance=0.08" },
	{ "segments=64", "arc_segments=2", "reflectance=0.16" },
};

static void scene(int i, struct tracer_scene *s)
{
	struct stray_error err;

	stray_error_clear(&err);
	tracer_scene_init(s);
	assert_int_equal(tracer_scene_load("ref4", sets[i], 3, s, &err), 0);
	assert_int_equal(tracer_scene_commit(s, &err), 0);
}

/* What the caller got: each trace's result, in the order they came. */
struct got {
	struct tracer_result r[N_TRACES];
	int have[N_TRACES], n_done, fail_at;
};

static int take_result(void *user, size_t i, struct tracer_result *res,
		       struct stray_error *err)
{
	struct got *g = user;

	assert_false(g->have[i]);
	g->r[i] = *res;
	memset(res, 0, sizeof(*res));
	g->have[i] = 1;
	if (++g->n_done == g->fail_at)
		return stray_error_set(err, STRAY_EIO, "test", "refused");
	return STRAY_OK;
}

static int drops[RANKS][N_TRACES];

static void drop(void *ctx, int rank, size_t trace)
{
	(void)ctx;
	drops[rank][trace]++;
}

/* Run the set on RANKS simulated ranks; fail_at: the callback refuses
 * the n-th trace (0: never).  Returns the number of pieces applied. */
static int simulate(struct tracer_trace_opts *o, struct tracer_scene *sc,
		    struct got *g, int fail_at)
{
	struct tracer_trace_item items[N_TRACES];
	struct farm_take q[RANKS][FARM_PREFETCH];
	unsigned char seen[RANKS][N_TRACES];
	int nq[RANKS] = { 0 }, r, step, applied = 0;
	struct farm_set fs;
	struct stray_error err;
	double *buf = NULL;
	size_t len, i;

	memset(items, 0, sizeof(items));
	memset(g, 0, sizeof(*g));
	memset(drops, 0, sizeof(drops));
	memset(seen, 0, sizeof(seen));
	g->fail_at = fail_at;
	for (i = 0; i < N_TRACES; i++) {
		items[i].spec.scene = "ref4";
		items[i].spec.sets = sets[i];
		items[i].spec.n_sets = 3;
		items[i].o = o;
	}
	stray_error_clear(&err);
	assert_int_equal(farm_set_init(&fs, items, N_TRACES, NULL, RANKS,
				       take_result, g, &err), 0);
	for (step = 0; !farm_set_finished(&fs); step++) {
		assert_true(step < 100000);
		for (r = 0; r < RANKS; r++)	/* feed every rank */
			while (nq[r] < FARM_PREFETCH &&
			       farm_set_take(&fs, r, &q[r][nq[r]])) {
				struct farm_take *t = &q[r][nq[r]++];
				const struct farm_trace *ft = &fs.t[t->trace];

				/* the job once, before the first piece */
				assert_int_equal(t->send_job,
						 !(seen[r][t->trace] & 1));
				seen[r][t->trace] |= 1;
				if (t->pass == PIECE_MAIN) {
					/* never before the trace's guide */
					assert_non_null(ft->g);
					assert_int_equal(t->send_guide,
						!(seen[r][t->trace] & 2));
					seen[r][t->trace] |= 2;
				}
			}
		/* one rank (in a scrambled turn) returns its newest piece */
		r = (step * 7 + 1) % RANKS;
		if (nq[r] == 0)
			continue;
		{
			struct farm_take *t = &q[r][--nq[r]];
			const struct farm_trace *ft = &fs.t[t->trace];

			assert_int_equal(piece_run_alloc(&sc[t->trace],
				&ft->pass[t->pass].o,
				t->pass == PIECE_MAIN ? ft->g : NULL,
				farm_set_piece(&fs, t), &buf, &len, &err), 0);
			assert_true(piece_payload_ok(farm_set_piece(&fs, t), 0,
						     buf, len));
			assert_int_equal(farm_set_apply(&fs, t, buf), 0);
			applied++;
		}
		farm_set_collect(&fs, drop, NULL);
	}
	if (!fail_at) {	/* every rank that built a scene lets it go */
		for (r = 1; r < RANKS; r++)
			for (i = 0; i < N_TRACES; i++)
				assert_int_equal(drops[r][i], seen[r][i] & 1);
	} else {
		assert_true(fs.failed);
		assert_string_equal(fs.err.reason, "refused");
	}
	free(buf);
	farm_set_free(&fs);
	return applied;
}

static void opts(struct tracer_trace_opts *o, const double *th, size_t n)
{
	tracer_trace_defaults(o);
	o->theta_deg = th;
	o->n_theta = n;
	o->n_paths = 12000;	/* >= 10000: the guided two-pass scheme */
	o->n_batches = 8;
	o->threads = 1;
}

/* The N_TRACES designs, farmed as one set at the angles th (fail_at:
 * as simulate's). */
static void farm_designs(const double *th, size_t n, int fail_at,
			 struct tracer_scene *sc, struct tracer_trace_opts *o,
			 struct got *g)
{
	int i;

	for (i = 0; i < N_TRACES; i++)
		scene(i, &sc[i]);
	opts(o, th, n);
	simulate(o, sc, g, fail_at);
}

static void release(struct tracer_scene *sc, struct got *g)
{
	int i;

	for (i = 0; i < N_TRACES; i++) {
		tracer_result_free(&g->r[i]);
		tracer_scene_free(&sc[i]);
	}
}

static void test_set_bits_of_each_trace(void **state)
{
	const double th[] = { 0, 10, 25, 40, 60, 80 };
	struct tracer_scene sc[N_TRACES];
	struct tracer_trace_opts o;
	struct got g;
	int i;

	(void)state;
	farm_designs(th, 6, 0, sc, &o, &g);
	for (i = 0; i < N_TRACES; i++) {
		struct tracer_result whole;
		struct stray_error err;

		assert_true(g.have[i]);
		stray_error_clear(&err);
		assert_int_equal(tracer_trace(&sc[i], &o, &whole, &err), 0);
		assert_memory_equal(whole.power, g.r[i].power,
				    (size_t)o.n_batches * o.n_theta *
				    TRACER_ORDERS * sizeof(double));
		assert_memory_equal(whole.energy, g.r[i].energy,
				    (size_t)o.n_batches * TRACER_ENERGY_N *
				    sizeof(double));
		assert_memory_equal(whole.batch_paths, g.r[i].batch_paths,
				    (size_t)o.n_batches * sizeof(uint64_t));
		if (i > 0)	/* the designs differ: a real comparison */
			assert_memory_not_equal(g.r[0].power, g.r[i].power,
				(size_t)o.n_batches * o.n_theta *
				TRACER_ORDERS * sizeof(double));
		tracer_result_free(&whole);
	}
	release(sc, &g);
}

/* Affinity: a rank stays on the traces whose scene it built while they
 * have pieces free, then opens a new trace, and joins another's only
 * once all are open; rank 0 here takes twice as often as the others. */
static void test_set_ranks_stay(void **state)
{
	static const int turn[4] = { 0, 0, 1, 2 };
	const double th[] = { 0, 30, 60 };
	struct tracer_trace_item items[N_TRACES];
	struct tracer_trace_opts o;
	struct farm_set fs;
	struct stray_error err;
	struct farm_take t;
	unsigned char seen[RANKS][N_TRACES];
	int r, builds = 0, i, j;

	(void)state;
	opts(&o, th, 3);
	o.n_paths = 5000;	/* no pilot: main pieces at once */
	o.n_batches = 16;
	memset(items, 0, sizeof(items));
	memset(seen, 0, sizeof(seen));
	for (i = 0; i < N_TRACES; i++) {
		items[i].spec.scene = "ref4";
		items[i].o = &o;
	}
	stray_error_clear(&err);
	assert_int_equal(farm_set_init(&fs, items, N_TRACES, NULL, RANKS,
				       take_result, NULL, &err), 0);
	for (i = 0; ; i++) {
		size_t was_open = fs.n_open;

		r = turn[i % 4];
		if (!farm_set_take(&fs, r, &t))
			break;
		builds += t.send_job;
		if (t.send_job)	/* nothing left in its own traces */
			for (j = 0; j < N_TRACES; j++)
				if (seen[r][j])
					assert_int_equal(
						fs.t[j].pass[PIECE_MAIN].next,
						fs.t[j].pass[PIECE_MAIN].n_plan);
		/* joined an open trace: only once all were open */
		if (t.send_job && t.trace < was_open)
			assert_int_equal(was_open, N_TRACES);
		seen[r][t.trace] = 1;
	}
	assert_int_equal(i, N_TRACES * 16);	/* every piece, once */
	/* each rank its own trace (3 scenes); at the end rank 0 joins
	 * trace 1, then rank 1 and rank 0 trace 2: 6, not all 9 */
	assert_int_equal(builds, 6);
	farm_set_free(&fs);
}

/* The caller refuses a trace (a blocked beam): the set stops. */
static void test_set_caller_failure(void **state)
{
	const double th[] = { 0, 30 };
	struct tracer_scene sc[N_TRACES];
	struct tracer_trace_opts o;
	struct got g;

	(void)state;
	farm_designs(th, 2, 1, sc, &o, &g);
	assert_int_equal(g.n_done, 1);
	release(sc, &g);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_set_bits_of_each_trace),
		cmocka_unit_test(test_set_ranks_stay),
		cmocka_unit_test(test_set_caller_failure),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
