/*
 * test_mesh_orient.c - a CAD mesh's winding found and made outward
 * (issue 23 item 4): a unit cube wound outward is left alone; wound
 * inward it is turned whole (its signed volume +1 after); two faces
 * turned are put back; the same cube split into two groups with their
 * own copies of the shared vertices (as assimp hands an OBJ's groups
 * over) is still one part; a Moebius strip is refused; the parametric
 * ref4 needs nothing turned.
 */
#include <stdlib.h>
#include <string.h>

#include "tracer_test.h"
#include "tracer/mesh_orient.h"
#include "tracer/scene_load.h"

/* The cube [0,1]^3, 12 triangles wound outward (right-handed). */
static const int cube_v[8][3] = {
	{0,0,0},{1,0,0},{1,1,0},{0,1,0},{0,0,1},{1,0,1},{1,1,1},{0,1,1}
};
static const int cube_t[12][3] = {
	{0,2,1},{0,3,2}, {4,5,6},{4,6,7}, {0,1,5},{0,5,4},
	{1,2,6},{1,6,5}, {2,3,7},{2,7,6}, {3,0,4},{3,4,7}
};

/* The cube; triangles from split on go to a second group with their own
 * vertex copies; those in turned[] are reversed. */
static void cube(struct tracer_mesh *m, int split, const int *turned, int nt)
{
	uint32_t idx[16];
	int i, t, g0, g1;

	tracer_mesh_init(m);
	g0 = tracer_mesh_group(m, "a", NULL);
	g1 = tracer_mesh_group(m, "b", NULL);
	for (i = 0; i < 16; i++)
		assert_int_equal(tracer_mesh_add_vertex(m, cube_v[i % 8][0],
			cube_v[i % 8][1], cube_v[i % 8][2], &idx[i], NULL), 0);
	for (t = 0; t < 12; t++) {
		int a = cube_t[t][0], b = cube_t[t][1], c = cube_t[t][2], k;
		int off = t >= split ? 8 : 0;

		for (k = 0; k < nt; k++)
			if (turned[k] == t) {
				int x = b;

				b = c;
				c = x;
			}
		assert_int_equal(tracer_mesh_add_triangle(m, idx[a + off],
			idx[b + off], idx[c + off], t >= split ? g1 : g0, NULL), 0);
	}
}

/* Six times the signed volume about the origin. */
static double volume6(const struct tracer_mesh *m)
{
	double v = 0.0;
	size_t t;

	for (t = 0; t < m->n_tri; t++) {
		const float *p = m->vert + 3 * m->tri[3 * t];
		const float *q = m->vert + 3 * m->tri[3 * t + 1];
		const float *r = m->vert + 3 * m->tri[3 * t + 2];

		v += p[0] * (q[1] * r[2] - q[2] * r[1]) -
		     p[1] * (q[0] * r[2] - q[2] * r[0]) +
		     p[2] * (q[0] * r[1] - q[1] * r[0]);
	}
	return v;
}

static void test_cube_cases(void **state)
{
	static const int all[12] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 };
	static const int two[2] = { 3, 8 };
	struct tracer_mesh m;
	struct tracer_orient_report r;

	(void)state;
	cube(&m, 12, NULL, 0);			/* outward: untouched */
	assert_int_equal(tracer_mesh_orient(&m, &r, NULL), 0);
	assert_int_equal(r.parts, 1);
	assert_int_equal(r.closed_parts, 1);
	assert_int_equal(r.turned_inconsistent + r.turned_inward, 0);
	assert_near(volume6(&m), 6.0, 1e-9);
	tracer_mesh_free(&m);

	cube(&m, 12, all, 12);			/* inward: turned whole */
	assert_near(volume6(&m), -6.0, 1e-9);
	assert_int_equal(tracer_mesh_orient(&m, &r, NULL), 0);
	assert_int_equal(r.inward_parts, 1);
	assert_int_equal(r.turned_inward, 12);
	assert_int_equal(r.turned_inconsistent, 0);
	assert_near(volume6(&m), 6.0, 1e-9);
	tracer_mesh_free(&m);

	cube(&m, 6, two, 2);			/* two faces turned, split */
	assert_int_equal(tracer_mesh_orient(&m, &r, NULL), 0);
	assert_int_equal(r.parts, 1);		/* joined across groups */
	assert_int_equal(r.closed_parts, 1);
	assert_int_equal(r.turned_inconsistent, 2);
	assert_int_equal(r.open_edges, 0);
	assert_near(volume6(&m), 6.0, 1e-9);
	tracer_mesh_free(&m);
}

/* A strip of 8 quads joined with a half twist cannot be oriented. */
static void test_moebius_refused(void **state)
{
	struct tracer_mesh m;
	struct tracer_orient_report r;
	struct stray_error err;
	uint32_t idx[16];
	int i, n = 8;

	(void)state;
	tracer_mesh_init(&m);
	tracer_mesh_group(&m, "strip", NULL);
	for (i = 0; i < n; i++) {
		double a = 6.283185307179586 * i / n, h = 0.3;
		double c = cos(a / 2) * h;

		assert_int_equal(tracer_mesh_add_vertex(&m, (2 + c) * cos(a),
			(2 + c) * sin(a), sin(a / 2) * h, &idx[2 * i], NULL), 0);
		assert_int_equal(tracer_mesh_add_vertex(&m, (2 - c) * cos(a),
			(2 - c) * sin(a), -sin(a / 2) * h, &idx[2 * i + 1], NULL), 0);
	}
	for (i = 0; i < n; i++) {
		uint32_t a = idx[2 * i], b = idx[2 * i + 1], c, d;

		if (i + 1 < n) {
			c = idx[2 * i + 2];
			d = idx[2 * i + 3];
		} else {	/* the half twist: the strip's sides swap */
			c = idx[1];
			d = idx[0];
		}
		tracer_mesh_add_triangle(&m, a, c, b, 0, NULL);
		tracer_mesh_add_triangle(&m, b, c, d, 0, NULL);
	}
	stray_error_clear(&err);
	assert_int_equal(tracer_mesh_orient(&m, &r, &err), STRAY_EINVAL);
	assert_non_null(strstr(err.reason, "cannot be oriented"));
	tracer_mesh_free(&m);
}

/* The parametric baffle is built outward: nothing to turn. */
static void test_ref4_untouched(void **state)
{
	struct tracer_scene s;
	struct tracer_orient_report r;
	uint32_t *before;
	size_t bytes;

	(void)state;
	tracer_scene_init(&s);
	assert_int_equal(tracer_scene_load("ref4", NULL, 0, &s, NULL), 0);
	bytes = 3 * s.mesh.n_tri * sizeof(uint32_t);
	before = malloc(bytes);
	memcpy(before, s.mesh.tri, bytes);
	assert_int_equal(tracer_mesh_orient(&s.mesh, &r, NULL), 0);
	if (r.turned_inconsistent + r.turned_inward)
		fail_msg("ref4: %zu parts (%zu closed), %zu turned to agree, "
			 "%zu in %zu inward parts", r.parts, r.closed_parts,
			 r.turned_inconsistent, r.turned_inward,
			 r.inward_parts);
	assert_memory_equal(before, s.mesh.tri, bytes);
	free(before);
	tracer_scene_free(&s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cube_cases),
		cmocka_unit_test(test_moebius_refused),
		cmocka_unit_test(test_ref4_untouched),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
