/*
 * test_diag_family.c - hidden effects on baffles other than ref4 (issue
 * 17 items 1, 2, 8): a 3-vane baffle of the vane family described by a
 * scene file, and the same baffle as a CAD mesh (exported to OBJ, read
 * back through a mesh scene file, knife edges through the mesh edge
 * model), and a narrower detector acceptance cone on the mesh.  The
 * truth is traced from its own scene (hidden edge radius and coating)
 * with its own seed; the analysis is told only the nominal scene file.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "diag_test.h"

static char dir[] = "/tmp/stray_family_XXXXXX";
static char fam[256], fam_truth[256], mesh[256], mesh_truth[256];

#define VANES3 \
	"{ \"type\": \"vanes\",\n" \
	"  \"vanes\": [ { \"z\": 0 }, { \"z\": -13 }, { \"z\": -26 } ],\n" \
	"  \"cone_half_angle_deg\": 10.5, \"segments\": 128,\n" \
	"  \"tube\": { \"inner_radius\": 20, \"wall\": 1.5 },\n" \
	"  \"pupil\": { \"radius\": 6.5, \"z\": -40 },\n"

static void write_file(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(text, f);
	assert_int_equal(fclose(f), 0);
}

static void mesh_scene(const char *path, double rho)
{
	char text[1024];

	snprintf(text, sizeof(text),
		 "{ \"meshes\": [ { \"file\": \"vanes3.obj\" } ],\n"
		 "  \"materials\": { \"black\": { \"type\": \"lambert\", "
		 "\"reflectance\": %g },\n"
		 "    \"shiny\": { \"type\": \"mirror\", \"reflectance\": 1 },\n"
		 "    \"dead\": { \"type\": \"absorber\" } },\n"
		 "  \"groups\": { \"exterior\": \"shiny\", \"detector\": "
		 "\"dead\" },\n"
		 "  \"default_material\": \"black\",\n"
		 "  \"detector\": { \"center\": [0, 0, -40], \"normal\": "
		 "[0, 0, 1], \"radius_mm\": 6.5 },\n"
		 "  \"beam\": { \"center\": [0, 0, 0], \"radius_mm\": "
		 "\"auto\" } }\n", rho);
	write_file(path, text);
}

static int setup(void **state)
{
	static struct cli_run r;
	char obj[256];
	char *argv[] = { "stray", "trace", "--scene", fam, "--angles", "0",
			 "--rays", "1000", "--export-obj", obj, "--out",
			 "/dev/null", NULL };

	(void)state;
	assert_non_null(mkdtemp(dir));
	snprintf(fam, sizeof(fam), "%s/vanes3.json", dir);
	snprintf(fam_truth, sizeof(fam_truth), "%s/vanes3_truth.json", dir);
	snprintf(mesh, sizeof(mesh), "%s/mesh.json", dir);
	snprintf(mesh_truth, sizeof(mesh_truth), "%s/mesh_truth.json", dir);
	snprintf(obj, sizeof(obj), "%s/vanes3.obj", dir);
	write_file(fam, VANES3 "  \"reflectance\": 0.04 }\n");
	/* the truth's own file: worn edges, a brighter coating */
	write_file(fam_truth, VANES3 "  \"reflectance\": 0.08, "
		   "\"edge_radius\": 0.08 }\n");
	run_stray(&r, argv);
	if (r.status != 0)
		fprintf(stderr, "export: %s\n", r.err);
	assert_int_equal(r.status, 0);
	mesh_scene(mesh, 0.04);
	mesh_scene(mesh_truth, 0.08);
	return 0;
}

static int teardown(void **state)
{
	char p[300];

	(void)state;
	unlink(fam);
	unlink(fam_truth);
	unlink(mesh);
	unlink(mesh_truth);
	snprintf(p, sizeof(p), "%s/vanes3.obj", dir);
	unlink(p);
	rmdir(dir);
	return 0;
}

/* Both hidden causes named, each truth inside its interval, nothing
 * else (no spurious angle offset from a clipped beam). */
static void expect_two(const char *test, const cJSON *j, double rho,
		       double radius)
{
	int in_rho = 0, in_r = 0;

	show(test, j);
	assert_true(flag(j, "significant"));
	assert_non_null(cause(j, "reflectance"));
	assert_non_null(cause(j, "knife_edge_radius"));
	param(cause(j, "reflectance"), "reflectance", rho, &in_rho);
	param(cause(j, "knife_edge_radius"), "radius_mm", radius, &in_r);
	assert_true(in_rho);
	assert_true(in_r);
	assert_int_equal(n_causes(j), 2);
	assert_true(num(j, "rms_after") < 0.5 * num(j, "rms_before"));
}

static void test_vanes3_file(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.scene = fam_truth;
	c.n_paths = 400000;
	j = diagnose_truth_on(&c, fam);
	expect_two(__func__, j, 0.08, 0.08);
	cJSON_Delete(j);
}

static void test_cad_mesh(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.scene = mesh_truth;
	c.sets[c.n_sets++] = "edge_radius=0.1";
	c.n_paths = 400000;
	j = diagnose_truth_on(&c, mesh);
	expect_two(__func__, j, 0.08, 0.1);
	cJSON_Delete(j);
}

/* A cause of the detector, not the geometry: on the mesh as on ref4. */
static void test_cad_mesh_acceptance(void **state)
{
	struct truth_config c;
	cJSON *j;

	(void)state;
	truth_defaults(&c, diag_test_theta, DIAG_TEST_N);
	c.scene = mesh;
	c.sets[c.n_sets++] = "accept_half_angle_deg=40";
	c.n_paths = 400000;
	j = diagnose_truth_on(&c, mesh);
	expect_one(__func__, j, "acceptance_cone", "half_angle_deg", 40.0);
	cJSON_Delete(j);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_vanes3_file),
		cmocka_unit_test(test_cad_mesh),
		cmocka_unit_test(test_cad_mesh_acceptance),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
