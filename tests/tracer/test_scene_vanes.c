/*
 * test_scene_vanes.c - the vane family as a scene file and the mesh edge
 * model (issue 17 items 1, 2): examples/ref4-vanes.json traces exactly
 * the bytes of the built-in ref4; a 3-vane file takes per-group
 * materials (shell patterns), `--set` overrides and names bad keys; the
 * knife edges of an exported OBJ, found by dihedral angle and rounded,
 * light the detector as the parametric fillet of the same radius does.
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../scratch.h"
#include "tracer_test.h"
#include "tracer/baffle.h"
#include "tracer/obj_export.h"
#include "tracer/scene_file.h"
#include "tracer/scene_load.h"

const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
	return "leak:libassimp.so\n";
}

static char dir[] = "/tmp/tracer_vanesXXXXXX";

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

static void put(const char *name, const char *text, char *path)
{
	FILE *f;

	sprintf(path, "%s/%s", dir, name);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static void load(const char *name, const char *const *sets, int n,
		 struct tracer_scene *s)
{
	struct stray_error err;

	stray_error_clear(&err);
	tracer_scene_init(s);
	if (tracer_scene_load(name, sets, n, s, &err))
		fail_msg("%s: %s %s", name, err.field ? err.field : "",
			 err.reason ? err.reason : "");
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

/* Same seed, same tallies: every batch's power equal, bit for bit. */
static void test_ref4_preset_bytes(void **state)
{
	const double th[] = { 0, 10, 27, 40, 60 };
	struct tracer_scene a, b;
	struct tracer_result ra, rb;

	(void)state;
	assert_int_equal(tracer_scene_file_is_vanes("examples/ref4-vanes.json"),
			 1);
	load("ref4", NULL, 0, &a);
	load("examples/ref4-vanes.json", NULL, 0, &b);
	assert_int_equal(a.mesh.n_tri, b.mesh.n_tri);
	{
		size_t i;

		for (i = 0; i < 3 * a.mesh.n_vert; i++)
			if (a.mesh.vert[i] != b.mesh.vert[i])
				fail_msg("vertex %zu: %.9g vs %.9g", i / 3,
					 a.mesh.vert[i], b.mesh.vert[i]);
	}
	assert_true(a.beam.radius_mm == b.beam.radius_mm);
	test_trace(&a, th, 5, 20000, 2, &ra);
	test_trace(&b, th, 5, 20000, 2, &rb);
	assert_memory_equal(ra.power, rb.power, (size_t)ra.n_batches * 5 *
			    TRACER_ORDERS * sizeof(*ra.power));
	tracer_result_free(&ra);
	tracer_result_free(&rb);
	tracer_scene_free(&a);
	tracer_scene_free(&b);
}

static const char vanes3[] =
	"{ \"type\": \"vanes\",\n"
	"  \"vanes\": [ { \"z\": 0 }, { \"z\": -13, \"aperture_mm\": 9.5 },\n"
	"              { \"z\": -26 } ],\n"
	"  \"vane_thickness\": 0.8, \"bevel_angle_deg\": 30,\n"
	"  \"bevel_face\": \"upper\", \"edge_radius\": 0.05, \"segments\": 64,\n"
	"  \"tube\": { \"inner_radius\": 18, \"wall\": 1 },\n"
	"  \"pupil\": { \"radius\": 6, \"z\": -38 },\n"
	"  \"materials\": { \"shiny\": { \"type\": \"lambert\", "
	"\"reflectance\": 0.3 },\n"
	"                 \"glossy\": { \"type\": \"abg\", \"reflectance\": "
	"0.05, \"a\": 0.01, \"b\": 0.01, \"g\": 2 } },\n"
	"  \"groups\": { \"vane*_edge\": \"shiny\", \"floor\": \"glossy\" } }\n";

static void test_family_file(void **state)
{
	const char *const sets[] = { "edge_radius=0.1", "reflectance=0.07" };
	struct tracer_scene s;
	struct tracer_baffle b;
	char path[256];
	int g;

	(void)state;
	put("v3.json", vanes3, path);
	load(path, sets, 2, &s);
	assert_int_equal(tracer_mesh_find_group(&s.mesh, "vane4_top"), -1);
	g = tracer_mesh_find_group(&s.mesh, "vane2_edge");
	assert_true(g >= 0);
	assert_near(s.material[g].rho, 0.3, 0);
	g = tracer_mesh_find_group(&s.mesh, "floor");
	assert_true(s.material[g].ops == &tracer_brdf_abg_ops);
	g = tracer_mesh_find_group(&s.mesh, "wall2");
	assert_near(s.material[g].rho, 0.07, 0);	/* the --set */
	/* the beam over-fills vane 1 as built: upper bevel, to its run */
	tracer_baffle_ref4(&b);
	b.vane_thickness = 0.8;
	b.bevel_angle_deg = 30;
	b.pupil_radius = 6;
	b.pupil_z = -38;
	b.vane_z[0] = 0;
	b.vane_z[2] = -26;
	b.n_vanes = 3;
	assert_near(s.beam.radius_mm, tracer_baffle_aperture(&b, 0) +
		    0.8 / tan(M_PI / 6.0) + 0.1, 1e-9);
	tracer_scene_free(&s);
}

static void expect_error(const char *text, const char *field)
{
	struct tracer_scene s;
	struct stray_error err;
	char path[256];

	put("bad.json", text, path);
	stray_error_clear(&err);
	tracer_scene_init(&s);
	assert_int_not_equal(tracer_scene_load(path, NULL, 0, &s, &err), 0);
	assert_true(err.column[0] || err.field);
	if (strcmp(err.column[0] ? err.column : err.field, field) != 0)
		fail_msg("error names '%s', not '%s'",
			 err.column[0] ? err.column : err.field, field);
	tracer_scene_free(&s);
}

static void test_family_errors(void **state)
{
	(void)state;
	expect_error("{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 } ], "
		     "\"colour\": 3 }", "colour");
	expect_error("{ \"type\": \"vanes\", \"vanes\": [] }", "vanes");
	expect_error("{ \"type\": \"vanes\", \"vanes\": [ { \"x\": 0 } ] }", "x");
	expect_error("{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 }, "
		     "{ \"z\": 5 } ] }", "vane_z");
	expect_error("{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 } ], "
		     "\"bevel_face\": \"side\" }", "bevel_face");
	expect_error("{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 } ], "
		     "\"groups\": { \"floor\": \"nope\" } }", "groups");
	expect_error("{ \"type\": \"cone\" }", "type");
}

static const char mesh_json[] =
	"{ \"meshes\": [ { \"file\": \"ref4.obj\" } ],\n"
	"  \"materials\": { \"black\": { \"type\": \"lambert\", "
	"\"reflectance\": 0.04 },\n"
	"    \"shiny\": { \"type\": \"mirror\", \"reflectance\": 1 },\n"
	"    \"dead\": { \"type\": \"absorber\" } },\n"
	"  \"groups\": { \"exterior\": \"shiny\", \"detector\": \"dead\" },\n"
	"  \"default_material\": \"black\",\n"
	"  \"detector\": { \"center\": [0, 0, -40], \"normal\": [0, 0, 1], "
	"\"radius_mm\": 6.5 },\n"
	"  \"beam\": { \"center\": [0, 0, 0], \"radius_mm\": \"auto\" } }\n";

/* single-scatter power at theta (index 1) and its sigma */
static void order1(const char *scene, const char *const *sets, int n,
		   double theta, double *p, double *sg, size_t *n_edge_groups)
{
	const double th[] = { 0, theta };
	struct tracer_scene s;
	struct tracer_result r;
	size_t g;

	load(scene, sets, n, &s);
	*n_edge_groups = 0;
	for (g = 0; g < s.mesh.n_group; g++)
		*n_edge_groups += strstr(s.mesh.group_name[g], "edge") != NULL &&
				  tracer_mesh_group_area(&s.mesh, (int)g) > 0.0;
	test_trace(&s, th, 2, 60000, 2, &r);
	tracer_result_power(&r, 1, 1, p, sg);
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

static void test_mesh_edges(void **state)
{
	const char *const p0[] = { "segments=128" };
	const char *const p1[] = { "segments=128", "edge_radius=0.1" };
	const char *const m1[] = { "edge_radius=0.1" };
	struct tracer_scene s;
	char obj[256], js[256];
	double a, sa, b, sb, c, sc;
	size_t ga, gb, gc;

	(void)state;
	load("ref4", p0, 1, &s);
	sprintf(obj, "%s/ref4.obj", dir);
	assert_int_equal(tracer_obj_export(&s.mesh, obj, NULL), 0);
	tracer_scene_free(&s);
	put("mesh.json", mesh_json, js);
	order1(js, NULL, 0, 40.0, &a, &sa, &ga);
	order1(js, m1, 1, 40.0, &b, &sb, &gb);
	order1("ref4", p1, 2, 40.0, &c, &sc, &gc);
	fprintf(stderr, "order-1 power at 40 deg: sharp mesh %.4g, rounded "
		"mesh %.4g +- %.2g, parametric fillet %.4g +- %.2g\n",
		a, b, sb, c, sc);
	assert_true(a == 0.0);		/* sharp: no lit face sees the pupil */
	assert_true(gb >= 4);		/* the four vane tips, at least */
	assert_true(b > 4.0 * sb);	/* rounded: the strips are lit */
	assert_near(b, c, 4.0 * hypot(sb, sc) + 0.1 * c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ref4_preset_bytes),
		cmocka_unit_test(test_family_file),
		cmocka_unit_test(test_family_errors),
		cmocka_unit_test(test_mesh_edges),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
