/*
 * test_scene_file.c - CAD scenes: the exported ref4 OBJ read back through
 * a JSON scene traces the same curve as the built-in baffle; STL (binary
 * and ASCII) imports into a named group and gives the closed-form aperture
 * transmission; malformed meshes and scene files fail with the file (and
 * line, for JSON) named.
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../scratch.h"
#include "tracer_test.h"
#include "tracer/baffle.h"
#include "tracer/mesh_import.h"
#include "tracer/obj_export.h"
#include "tracer/scene_file.h"

static char dir[] = "/tmp/tracer_sceneXXXXXX";

/*
 * assimp 5.2 leaks two small objects when an import throws (its exception
 * path in the C API), never ours: the LeakSanitizer hook for this binary
 * (tests/lsan.supp's rule: third-party process-life allocations only).
 */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
	return "leak:libassimp.so\n";
}

static int setup(void **state)
{
	(void)state;
	return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

static void put(const char *name, const char *text, size_t len, char *path)
{
	FILE *f;

	sprintf(path, "%s/%s", dir, name);
	f = fopen(path, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(text, 1, len, f), len);
	fclose(f);
}

static const char ref4_json[] =
	"{ \"meshes\": [ { \"file\": \"ref4.obj\" } ],\n"
	"  \"materials\": { \"black\": { \"type\": \"lambert\", "
	"\"reflectance\": 0.04 },\n"
	"    \"exterior\": { \"type\": \"mirror\", \"reflectance\": 1 },\n"
	"    \"detector\": { \"type\": \"absorber\" } },\n"
	"  \"default_material\": \"black\",\n"
	"  \"detector\": { \"shape\": \"disk\", \"center\": [0, 0, -40],\n"
	"    \"normal\": [0, 0, 1], \"radius_mm\": 6.5 },\n"
	"  \"beam\": { \"center\": [0, 0, 0], \"radius_mm\": 14.0136 } }\n";

static void test_scene_file_obj_round_trip(void **state)
{
	const double th[] = { 0, 20, 35, 60 };
	struct tracer_baffle b;
	struct tracer_scene s1, s2;
	struct tracer_result r1, r2;
	char obj[256], js[256];
	size_t j;

	(void)state;
	tracer_baffle_ref4(&b);
	b.segments = 128;
	tracer_scene_init(&s1);
	assert_int_equal(tracer_baffle_build(&b, &s1, NULL), 0);
	sprintf(obj, "%s/ref4.obj", dir);
	assert_int_equal(tracer_obj_export(&s1.mesh, obj, NULL), 0);
	put("ref4.json", ref4_json, sizeof(ref4_json) - 1, js);
	tracer_scene_init(&s2);
	assert_int_equal(tracer_scene_file_load(js, &s2, NULL), 0);
	assert_int_equal(s2.mesh.n_tri, s1.mesh.n_tri);
	/* every group that has triangles comes back, by name */
	for (j = 0; j < s1.mesh.n_group; j++)
		if (tracer_mesh_group_area(&s1.mesh, (int)j) > 0.0)
			assert_true(tracer_mesh_find_group(&s2.mesh,
				    s1.mesh.group_name[j]) >= 0);
	assert_int_equal(tracer_scene_commit(&s1, NULL), 0);
	assert_int_equal(tracer_scene_commit(&s2, NULL), 0);
	test_trace(&s1, th, 4, 40000, 2, &r1);
	test_trace(&s2, th, 4, 40000, 2, &r2);
	for (j = 1; j < 4; j++) {
		double a1, e1, a2, e2;

		tracer_result_alpha(&r1, j, 0, -1, &a1, &e1);
		tracer_result_alpha(&r2, j, 0, -1, &a2, &e2);
		assert_near(a2, a1, 3.0 * hypot(e1, e2) + 1e-6 * a1);
	}
	tracer_result_free(&r1);
	tracer_result_free(&r2);
	tracer_scene_free(&s1);
	tracer_scene_free(&s2);
}

/* A square plate (side 80) with a square hole (side 2h) as binary STL. */
static size_t plate_stl(char *buf, double h)
{
	const double o = 40.0;
	const float quad[4][4][2] = {
		{ { -o, -o }, { o, -o }, { o, -h }, { -o, -h } },
		{ { -o, h }, { o, h }, { o, o }, { -o, o } },
		{ { -o, -h }, { -h, -h }, { -h, h }, { -o, h } },
		{ { h, -h }, { o, -h }, { o, h }, { h, h } },
	};
	uint32_t n = 8;
	size_t at = 80;
	int q, t, k;

	memset(buf, 0, 84 + 50 * 8);
	memcpy(buf + at, &n, 4);
	at += 4;
	for (q = 0; q < 4; q++)
		for (t = 0; t < 2; t++) {
			const int idx[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
			float v[12] = { 0, 0, 1 };

			for (k = 0; k < 3; k++) {
				v[3 + 3 * k] = quad[q][idx[t][k]][0];
				v[4 + 3 * k] = quad[q][idx[t][k]][1];
				v[5 + 3 * k] = 0.0f;
			}
			memcpy(buf + at, v, 48);
			at += 50;
		}
	return at;
}

/* Through a square hole of half-side h onto a detector disk of radius
 * b < h at depth d: direct light is cos(theta) while the disk's shadow
 * window (shifted by d tan theta) still contains it. */
static void test_scene_file_stl_plate(void **state)
{
	static char buf[1024];
	const double th[] = { 0, 10, 30 };
	char stl[256], js[256];
	const char *json =
		"{ \"meshes\": [ { \"file\": \"plate.stl\", "
		"\"group\": \"plate\" } ],\n"
		"  \"materials\": { \"plate\": { \"type\": \"absorber\" } },\n"
		"  \"detector\": { \"center\": [0, 0, -2], \"normal\": [0, 0, 1],"
		" \"radius_mm\": 1 },\n"
		"  \"beam\": { \"center\": [0, 0, 0], \"radius_mm\": 50 } }\n";
	struct tracer_scene s;
	struct tracer_result r;
	double p, sg;

	(void)state;
	put("plate.stl", buf, plate_stl(buf, 5.0), stl);
	put("plate.json", json, strlen(json), js);
	tracer_scene_init(&s);
	assert_int_equal(tracer_scene_file_load(js, &s, NULL), 0);
	assert_int_equal(s.mesh.n_tri, 8);
	assert_string_equal(s.mesh.group_name[0], "plate");
	assert_int_equal(tracer_scene_commit(&s, NULL), 0);
	test_trace(&s, th, 3, 2000, 1, &r);
	tracer_result_power(&r, 1, 0, &p, &sg);
	assert_near(p, cos(10.0 * M_PI / 180.0), 1e-12);	/* fully open */
	tracer_result_power(&r, 2, 0, &p, &sg);
	assert_near(p, cos(30.0 * M_PI / 180.0), 1e-12);
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* Refused, naming the file and where: a line, or a byte offset. */
static void expect_mesh_error(const char *name, const char *text, size_t n,
			      long line, const char *where)
{
	struct tracer_mesh m;
	struct stray_error err;
	char path[256];

	put(name, text, n, path);
	tracer_mesh_init(&m);
	stray_error_clear(&err);
	assert_int_equal(tracer_mesh_import(&m, path, NULL, 1.0, &err),
			 STRAY_EPARSE);
	assert_string_equal(err.file, path);
	assert_true(strlen(err.text) > 0);	/* the importer's reason */
	assert_int_equal(err.line, line);
	if (where && !strstr(err.text, where))
		fail_msg("'%s' does not say '%s'", err.text, where);
	tracer_mesh_free(&m);
}

static void test_scene_file_malformed_meshes(void **state)
{
	static const char bad_index[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
	static const char bad_number[] = "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n";
	static const char bad_ascii[] = "solid x\nfacet normal 0 0 1\n"
		"outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1\n"
		"endloop\nendfacet\nendsolid\n";
	static char trunc[200];
	uint32_t n = 1000;

	(void)state;
	expect_mesh_error("bad_index.obj", bad_index, sizeof(bad_index) - 1,
			  4, NULL);
	expect_mesh_error("bad_number.obj", bad_number, sizeof(bad_number) - 1,
			  2, NULL);
	expect_mesh_error("bad_ascii.stl", bad_ascii, sizeof(bad_ascii) - 1,
			  6, NULL);
	memcpy(trunc + 80, &n, 4);	/* claims 1000 facets, holds 2 */
	expect_mesh_error("truncated.stl", trunc, sizeof(trunc), 0,
			  "byte 200: 1000 facets declared need 50084 bytes");
	expect_mesh_error("empty.obj", "# nothing\n", 10, 0, NULL);
}

static void expect_scene_error(const char *json, int code, const char *field,
			       long line)
{
	const char *culprit = strstr(json, "nope.obj") ? "nope.obj" : "bad.json";
	struct tracer_scene s;
	struct stray_error err;
	char path[256];

	put("bad.json", json, strlen(json), path);
	tracer_scene_init(&s);
	stray_error_clear(&err);
	assert_int_equal(tracer_scene_file_load(path, &s, &err), code);
	assert_non_null(strstr(err.file, culprit));
	if (field)
		assert_string_equal(err.field, field);
	if (line)
		assert_int_equal(err.line, line);
	tracer_scene_free(&s);
}

static void test_scene_file_bad_scenes_named(void **state)
{
	static char buf[1024];
	char stl[256];

	(void)state;
	put("plate.stl", buf, plate_stl(buf, 5.0), stl);
	expect_scene_error("{\n \"meshes\": [\n  { \"file\": } ]\n}\n",
			   STRAY_EPARSE, "--scene", 3);
	expect_scene_error("{ \"meshes\": [] }", STRAY_EINVAL, "meshes", 0);
	expect_scene_error("{ \"meshes\": [ { \"file\": \"plate.stl\" } ],"
			   " \"materials\": {} }", STRAY_ENOTFOUND, "groups", 0);
	expect_scene_error("{ \"meshes\": [ { \"file\": \"plate.stl\" } ],"
			   " \"materials\": { \"m\": { \"type\": \"glass\" } },"
			   " \"default_material\": \"m\" }", STRAY_EINVAL,
			   "type", 0);
	expect_scene_error("{ \"meshes\": [ { \"file\": \"plate.stl\" } ],"
			   " \"materials\": { \"m\": { \"type\": \"lambert\","
			   " \"reflectance\": 2 } }, \"default_material\": \"m\""
			   " }", STRAY_EINVAL, "reflectance", 0);
	expect_scene_error("{ \"meshes\": [ { \"file\": \"plate.stl\" } ],"
			   " \"materials\": { \"m\": { \"type\": \"absorber\" } },"
			   " \"default_material\": \"m\", \"beam\": {} }",
			   STRAY_EINVAL, "detector", 0);
	expect_scene_error("{ \"meshes\": [ { \"file\": \"nope.obj\" } ] }",
			   STRAY_EPARSE, "mesh", 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_scene_file_obj_round_trip),
		cmocka_unit_test(test_scene_file_stl_plate),
		cmocka_unit_test(test_scene_file_malformed_meshes),
		cmocka_unit_test(test_scene_file_bad_scenes_named),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
