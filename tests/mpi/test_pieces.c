/*
 * test_pieces.c - a trace cut into pieces (angle chunk x batch), run in a
 * scrambled order and put back together, is bit-identical to one
 * tracer_trace() call with the same seed, pilot and guide included: the
 * property that lets stray-mpi hand pieces to any rank in any order.
 * No MPI here; tests/mpi/test_mpi_*.c check the same through mpirun.
 */
#include <string.h>

#include "piece.h"
#include "tracer_test.h"
#include "tracer/scene_load.h"

/* The ref4 baffle, built in (ref4-baffle.md), made coarse to be quick. */
static void ref4(struct tracer_scene *s)
{
	static const char *const sets[] = { "segments=64", "arc_segments=2" };
	struct stray_error err;

	stray_error_clear(&err);
	tracer_scene_init(s);
	assert_int_equal(tracer_scene_load("ref4", sets, 2, s, &err), 0);
	assert_int_equal(tracer_scene_commit(s, &err), 0);
}

/* Run every piece of pass po in a scrambled order into r (and s2). */
static void run_scrambled(const struct tracer_scene *s,
			  const struct tracer_trace_opts *po,
			  const struct tracer_guide *g, int pass, int chunks,
			  struct tracer_result *r, double **s2)
{
	struct piece plan[64 * 8];
	struct stray_error err;
	size_t n, i;
	double *buf;

	n = piece_plan(pass, po->n_batches, po->n_theta, chunks, plan);
	assert_int_equal(n, (size_t)po->n_batches * chunks);
	assert_int_equal(piece_result_alloc(po, r, pass == PIECE_PILOT ? s2 :
					    NULL), 0);
	for (i = 0; i < n; i++) {
		/* 7 is prime to n here: every piece once, out of order */
		const struct piece *p = &plan[(i * 7 + 3) % n];

		buf = malloc(piece_payload_len(p) * sizeof(double));
		stray_error_clear(&err);
		assert_int_equal(piece_run(s, po, g, p, buf, &err), 0);
		piece_apply(p, buf, r, pass == PIECE_PILOT ? *s2 : NULL, NULL);
		free(buf);
	}
}

static void check_identical(int chunks)
{
	const double th[] = { 0, 10, 25, 40, 60, 80 };
	struct tracer_trace_opts o, po;
	struct tracer_scene s;
	struct tracer_result whole, pilot, parts;
	struct tracer_guide g;
	struct stray_error err;
	double *s2 = NULL;
	size_t j;

	ref4(&s);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 6;
	o.n_paths = 12000;	/* >= 10000: the guided two-pass scheme */
	o.n_batches = 8;
	o.threads = 2;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &whole, &err), 0);
	assert_true(tracer_pilot_wanted(&o));
	tracer_pilot_opts(&o, &po);
	run_scrambled(&s, &po, NULL, PIECE_PILOT, chunks, &pilot, &s2);
	assert_int_equal(tracer_guide_from_pilot(&g, &pilot, s2), 0);
	run_scrambled(&s, &o, &g, PIECE_MAIN, chunks, &parts, NULL);
	assert_memory_equal(whole.power, parts.power, (size_t)o.n_batches *
			    o.n_theta * TRACER_ORDERS * sizeof(double));
	assert_memory_equal(whole.energy, parts.energy, (size_t)o.n_batches *
			    TRACER_ENERGY_N * sizeof(double));
	assert_memory_equal(whole.batch_paths, parts.batch_paths,
			    (size_t)o.n_batches * sizeof(uint64_t));
	for (j = 1; j < o.n_theta; j++) {
		double a1, s1, a2, s2v;

		tracer_result_alpha(&whole, j, 0, -1, &a1, &s1);
		tracer_result_alpha(&parts, j, 0, -1, &a2, &s2v);
		assert_memory_equal(&a1, &a2, sizeof(double));
		assert_memory_equal(&s1, &s2v, sizeof(double));
	}
	{	/* scattered light reached the detector: a real comparison */
		double scat = 0.0;
		size_t i;

		for (i = 0; i < (size_t)o.n_batches * o.n_theta; i++)
			scat += whole.power[i * TRACER_ORDERS + 1];
		assert_true(scat > 0.0);
	}
	/* one chunk: the same work; more: paths retraced per chunk */
	if (chunks == 1)
		assert_int_equal(whole.casts, parts.casts);
	else
		assert_true(parts.casts > whole.casts);
	tracer_result_free(&whole);
	tracer_result_free(&pilot);
	tracer_result_free(&parts);
	free(s2);
	tracer_scene_free(&s);
}

static void test_pieces_batches_only(void **state)
{
	(void)state;
	check_identical(1);
}

static void test_pieces_angle_chunks(void **state)
{
	(void)state;
	check_identical(3);
}

/* A different guide gives different bits: the check above can fail. */
static void test_pieces_guide_matters(void **state)
{
	const double th[] = { 0, 30, 60 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct tracer_result whole, parts;
	struct stray_error err;

	(void)state;
	ref4(&s);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 3;
	o.n_paths = 12000;
	o.n_batches = 8;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &whole, &err), 0);
	run_scrambled(&s, &o, NULL, PIECE_MAIN, 1, &parts, NULL);
	assert_memory_not_equal(whole.power, parts.power, (size_t)o.n_batches *
				o.n_theta * TRACER_ORDERS * sizeof(double));
	tracer_result_free(&whole);
	tracer_result_free(&parts);
	tracer_scene_free(&s);
}

/* Path records (stray-mpi diagnose): pieces in a scrambled order, their
 * records merged per batch, then in batch order, hold the sums of the
 * whole trace's table, bit for bit (slots may differ). */
static void test_pieces_path_records(void **state)
{
	const double th[] = { 0, 10, 25, 40, 60, 80 };
	struct tracer_path_table tables[8];
	struct tracer_trace_opts o, po;
	struct tracer_scene s;
	struct tracer_result whole, pilot, parts;
	struct tracer_guide g;
	struct stray_error err;
	struct piece plan[8 * 3];
	double *s2 = NULL, *buf = NULL;
	size_t n, i, len;

	(void)state;
	ref4(&s);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 6;
	o.n_paths = 12000;
	o.n_batches = 8;
	o.record_paths = 1;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &whole, &err), 0);
	tracer_pilot_opts(&o, &po);
	run_scrambled(&s, &po, NULL, PIECE_PILOT, 3, &pilot, &s2);
	assert_int_equal(tracer_guide_from_pilot(&g, &pilot, s2), 0);
	memset(tables, 0, sizeof(tables));
	n = piece_plan(PIECE_MAIN, o.n_batches, o.n_theta, 3, plan);
	assert_int_equal(piece_result_alloc(&o, &parts, NULL), 0);
	for (i = 0; i < n; i++) {
		const struct piece *p = &plan[(i * 7 + 3) % n];

		assert_int_equal(piece_run_alloc(&s, &o, &g, p, &buf, &len,
						 &err), 0);
		assert_true(piece_payload_ok(p, 1, buf, len));
		assert_false(piece_payload_ok(p, 1, buf, len - 1));
		piece_apply(p, buf, &parts, NULL, NULL);
		assert_int_equal(piece_apply_paths(p, buf, tables), 0);
	}
	for (i = 0; i < 8; i++) {
		assert_int_equal(tracer_paths_merge(&parts.paths, &tables[i]),
				 0);
		tracer_paths_free(&tables[i]);
	}
	assert_true(whole.paths.n > 10);	/* scatter sequences recorded */
	assert_int_equal(whole.paths.n, parts.paths.n);
	for (i = 0; i < whole.paths.cap; i++) {
		const struct tracer_path_entry *a = &whole.paths.e[i], *b;

		if (!a->used)
			continue;
		b = tracer_paths_find(&parts.paths, a->theta_index, a->seq);
		assert_non_null(b);
		assert_memory_equal(&a->value, &b->value, sizeof(double));
		assert_memory_equal(&a->value_b2, &b->value_b2, sizeof(double));
		assert_memory_equal(&a->n_paths, &b->n_paths, sizeof(double));
	}
	free(buf);
	free(s2);
	tracer_result_free(&whole);
	tracer_result_free(&pilot);
	tracer_result_free(&parts);
	tracer_scene_free(&s);
}

/*
 * Strategy B (opts.light_paths) in pieces: pilot pieces in 3 angle chunks
 * in a scrambled order return B's statistics beside s2, and their casts
 * are summed once per batch, so the pilot assembled is the whole
 * pilot's (light rows, casts: what tracer_light_alloc reads); its ratios
 * and guide then give main pieces the bits of tracer_trace().
 */
static void test_pieces_light(void **state)
{
	const double th[] = { 0, 60, 80, 88.5, 89, 89.5 };
	struct tracer_trace_opts o, po;
	struct tracer_scene s;
	struct tracer_result whole, one, pilot, parts;
	struct tracer_guide g;
	struct stray_error err;
	struct piece plan[8 * 3];
	size_t n, i, nl = 8 * 6 * TRACER_LIGHT_STATS;
	double *s2, *s2_one, *light, *light_one, ratio[6], *buf = NULL;

	(void)state;
	ref4(&s);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 6;
	o.n_paths = 20000;
	o.n_batches = 8;
	o.light_paths = 1;
	stray_error_clear(&err);
	assert_int_equal(tracer_trace(&s, &o, &whole, &err), 0);
	tracer_pilot_opts(&o, &po);
	s2_one = calloc(8 * TRACER_GUIDE_CELLS * 6, sizeof(double));
	light_one = calloc(nl, sizeof(double));
	light = calloc(nl, sizeof(double));
	assert_non_null(s2_one);
	assert_non_null(light_one);
	assert_non_null(light);
	assert_int_equal(tracer_trace_batches_light(&s, &po, NULL, 0, 8,
		s2_one, light_one, &one, &err), 0);
	n = piece_plan(PIECE_PILOT, 8, 6, 3, plan);
	assert_int_equal(piece_result_alloc(&po, &pilot, &s2), 0);
	for (i = 0; i < n; i++) {
		struct piece p = plan[(i * 7 + 3) % n];
		size_t len;

		p.light = 1;
		assert_int_equal(piece_run_alloc(&s, &po, NULL, &p, &buf, &len,
						 &err), 0);
		assert_true(piece_payload_ok(&p, 0, buf, len));
		assert_false(piece_payload_ok(&p, 0, buf, len + 1));
		piece_apply(&p, buf, &pilot, s2, light);
	}
	assert_memory_equal(light, light_one, nl * sizeof(double));
	assert_memory_equal(s2, s2_one, 8 * TRACER_GUIDE_CELLS * 6 *
			    sizeof(double));
	assert_int_equal(pilot.casts, one.casts);
	assert_int_equal(tracer_guide_from_pilot(&g, &pilot, s2), 0);
	tracer_light_alloc(&pilot, light, ratio);
	assert_true(ratio[5] > 0.0);	/* B does run at 89.5 deg */
	o.light_ratio = ratio;
	run_scrambled(&s, &o, &g, PIECE_MAIN, 3, &parts, NULL);
	assert_memory_equal(whole.power, parts.power, (size_t)8 * 6 *
			    TRACER_ORDERS * sizeof(double));
	/* a light flag on a pass without light_paths is refused */
	po.light_paths = 0;
	plan[0].light = 1;
	assert_int_equal(piece_run_alloc(&s, &po, NULL, &plan[0], &buf, &n,
					 &err), STRAY_EINVAL);
	free(buf);
	free(s2);
	free(s2_one);
	free(light);
	free(light_one);
	tracer_result_free(&whole);
	tracer_result_free(&one);
	tracer_result_free(&pilot);
	tracer_result_free(&parts);
	tracer_scene_free(&s);
}

/* Bad pieces are refused with an error, never traced out of range. */
static void test_pieces_bad_range(void **state)
{
	const double th[] = { 0, 30 };
	struct tracer_trace_opts o;
	struct tracer_scene s;
	struct stray_error err;
	struct piece p = { PIECE_MAIN, 0, 1, 2, 0 };
	double buf[64];

	(void)state;
	ref4(&s);
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = 2;
	o.n_paths = 100;
	o.n_batches = 4;
	stray_error_clear(&err);
	assert_int_equal(piece_run(&s, &o, NULL, &p, buf, &err), STRAY_EINVAL);
	p.theta_first = 0;
	p.theta_n = 1;
	p.batch = 4;
	stray_error_clear(&err);
	assert_int_equal(piece_run(&s, &o, NULL, &p, buf, &err), STRAY_EINVAL);
	tracer_scene_free(&s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_pieces_batches_only),
		cmocka_unit_test(test_pieces_angle_chunks),
		cmocka_unit_test(test_pieces_guide_matters),
		cmocka_unit_test(test_pieces_path_records),
		cmocka_unit_test(test_pieces_light),
		cmocka_unit_test(test_pieces_bad_range),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
