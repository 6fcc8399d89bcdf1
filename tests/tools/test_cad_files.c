/*
 * test_cad_files.c - CAD meshes as engineers export them (issue 23 item
 * 4), through `stray trace` as a user runs it: ref4 exported to OBJ,
 * then the same mesh (1) wound inward, (2) in metres, (3) as two binary
 * STL files, one a part of its own with its own coating.
 *
 * Before: the inward mesh traced without a word and its knife edges were
 * not rounded (alpha(40 deg) 39 % low with edge_radius 0.1 mm); the mesh
 * in metres traced as if there were no baffle (alpha(20) = 0.368).
 * STRAY_BIN=/path/to/old/stray runs the same probes on another build.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "../scratch.h"
#include "../test_util.h"
#include "run_cli.h"

static struct cli_run r;
static char dir[] = "/tmp/stray_cadXXXXXX";

#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })

static char *at(const char *name)
{
	static char p[8][256];
	static int k;
	char *s = p[k++ % 8];

	snprintf(s, 256, "%s/%s", dir, name);
	return s;
}

static void scene(const char *name, const char *meshes)
{
	FILE *f = fopen(at(name), "w");

	assert_non_null(f);
	fprintf(f, "{ \"meshes\": [ %s ],\n"
		"  \"materials\": { \"black\": { \"type\": \"lambert\", "
		"\"reflectance\": 0.04 }, \"exterior\": { \"type\": \"mirror\", "
		"\"reflectance\": 1 }, \"detector\": { \"type\": \"absorber\" } },\n"
		"  \"default_material\": \"black\",\n"
		"  \"detector\": { \"shape\": \"disk\", \"center\": [0, 0, -40], "
		"\"normal\": [0, 0, 1], \"radius_mm\": 6.5 },\n"
		"  \"beam\": { \"center\": [0, 0, 0], \"radius_mm\": 14.0136 } }\n",
		meshes);
	fclose(f);
}

/* The exported OBJ rewritten: faces reversed, or vertices scaled. */
static void rewrite_obj(const char *out, int reverse, double scale)
{
	FILE *in = fopen(at("ref4.obj"), "r"), *o = fopen(at(out), "w");
	char line[256];

	assert_non_null(in);
	assert_non_null(o);
	while (fgets(line, sizeof(line), in)) {
		double x, y, z;
		long a, b, c;

		if (reverse && sscanf(line, "f %ld %ld %ld", &a, &b, &c) == 3)
			fprintf(o, "f %ld %ld %ld\n", a, c, b);
		else if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3)
			fprintf(o, "v %.9g %.9g %.9g\n", x * scale, y * scale,
				z * scale);
		else
			fputs(line, o);
	}
	fclose(in);
	fclose(o);
}

/* The OBJ as two binary STL files: group "exterior" and the rest. */
static void write_stls(void)
{
	FILE *in = fopen(at("ref4.obj"), "r");
	FILE *o[2] = { fopen(at("baffle.stl"), "wb"), fopen(at("ext.stl"), "wb") };
	static float v[20000][3];
	uint32_t n[2] = { 0, 0 };
	char line[256], hdr[80] = "binary STL written by test_cad_files";
	int nv = 0, ext = 0, k;

	assert_non_null(in);
	for (k = 0; k < 2; k++) {
		fwrite(hdr, 1, 80, o[k]);
		fwrite(&n[k], 4, 1, o[k]);	/* patched below */
	}
	while (fgets(line, sizeof(line), in)) {
		long a, b, c;

		if (sscanf(line, "v %f %f %f", &v[nv][0], &v[nv][1],
			   &v[nv][2]) == 3)
			nv++;
		else if (!strncmp(line, "g ", 2))
			ext = !strncmp(line + 2, "exterior", 8);
		else if (sscanf(line, "f %ld %ld %ld", &a, &b, &c) == 3) {
			float rec[12] = { 0, 0, 0 };
			uint16_t attr = 0;

			memcpy(rec + 3, v[a - 1], 12);
			memcpy(rec + 6, v[b - 1], 12);
			memcpy(rec + 9, v[c - 1], 12);
			fwrite(rec, 4, 12, o[ext]);
			fwrite(&attr, 2, 1, o[ext]);
			n[ext]++;
		}
	}
	fclose(in);
	for (k = 0; k < 2; k++) {
		fseek(o[k], 80, SEEK_SET);
		fwrite(&n[k], 4, 1, o[k]);
		fclose(o[k]);
	}
	assert_true(n[0] > 1000 && n[1] > 100);
}

/* alpha at the curve's rows, from a curve CSV. */
static int alphas(const char *name, double *a, double *s)
{
	FILE *f = fopen(at(name), "r");
	char line[512];
	int n = 0;

	assert_non_null(f);
	while (fgets(line, sizeof(line), f))
		if (line[0] != '#' && line[0] != 't' &&
		    sscanf(line, "%*f,%lf,%lf", &a[n], &s[n]) == 2)
			n++;
	fclose(f);
	return n;
}

static int setup(void **state)
{
	(void)state;
	if (!mkdtemp(dir))
		return -1;
	/* the exporter's own OBJ: one group per surface group */
	return STRAY("trace", "--scene", "ref4", "--export-obj",
		     at("ref4.obj")) == 0 ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

#define TRACE(scn, out, ...) STRAY("trace", "--scene", at(scn), "--angles", \
	"0,20,40,60", "--rays", "30000", "--out", at(out), __VA_ARGS__)

static void test_inward_turned_and_said(void **state)
{
	double a[8], s[8], b[8], t[8];
	int i;

	(void)state;
	rewrite_obj("inward.obj", 1, 1.0);
	scene("out.json", "{ \"file\": \"ref4.obj\" }");
	scene("in.json", "{ \"file\": \"inward.obj\" }");
	assert_int_equal(TRACE("out.json", "out.csv", "--set",
			       "edge_radius=0.1"), 0);
	assert_int_equal(TRACE("in.json", "in.csv", "--set",
			       "edge_radius=0.1"), 0);
	if (!strstr(r.err, "wound inward") || !strstr(r.err, "turned outward"))
		fail_msg("no word of the winding: '%s'", r.err);
	assert_int_equal(alphas("out.csv", a, s), 4);
	assert_int_equal(alphas("in.csv", b, t), 4);
	for (i = 0; i < 4; i++)		/* the same mesh, so the same bits */
		if (a[i] != b[i])
			fail_msg("row %d: alpha %.10g outward, %.10g inward",
				 i, a[i], b[i]);
}

static void test_metres_refused_then_scaled(void **state)
{
	double a[8], s[8], b[8], t[8];
	int i;

	(void)state;
	rewrite_obj("metres.obj", 0, 1e-3);
	scene("m.json", "{ \"file\": \"metres.obj\" }");
	TRACE("m.json", "m.csv", "--threads", "1");
	if (r.status != 2 || !strstr(r.err, "scale_mm") ||
	    !strstr(r.err, "metres"))
		fail_msg("status %d: %s", r.status, r.err);
	scene("m1000.json", "{ \"file\": \"metres.obj\", \"scale_mm\": 1000 }");
	scene("out.json", "{ \"file\": \"ref4.obj\" }");
	assert_int_equal(TRACE("m1000.json", "m.csv", "--threads", "1"), 0);
	assert_int_equal(TRACE("out.json", "out.csv", "--threads", "1"), 0);
	assert_int_equal(alphas("m.csv", a, s), 4);
	assert_int_equal(alphas("out.csv", b, t), 4);
	for (i = 1; i < 4; i++)	/* rounded to 9 digits and back: 3 sigma */
		if (fabs(a[i] - b[i]) > 3.0 * hypot(s[i], t[i]) + 1e-12)
			fail_msg("row %d: %.6g +- %.2g scaled, %.6g +- %.2g",
				 i, a[i], s[i], b[i], t[i]);
}

/* Two STL files, each its own part and coating: with the exterior a
 * mirror as in the OBJ, the OBJ's curve; with the baffle a mirror too
 * (the part named "exterior"), another. */
static void test_stl_parts_take_their_coatings(void **state)
{
	double a[8], s[8], b[8], t[8], c[8], u[8];
	int i, differs = 0;

	(void)state;
	write_stls();
	scene("stl.json", "{ \"file\": \"baffle.stl\", \"group\": \"baffle\" }, "
	      "{ \"file\": \"ext.stl\", \"group\": \"exterior\" }");
	scene("stl1.json", "{ \"file\": \"baffle.stl\", \"group\": "
	      "\"exterior\" }, { \"file\": \"ext.stl\", \"group\": "
	      "\"exterior\" }");
	scene("out.json", "{ \"file\": \"ref4.obj\" }");
	assert_int_equal(TRACE("stl.json", "stl.csv", "--threads", "1"), 0);
	assert_int_equal(TRACE("stl1.json", "stl1.csv", "--threads", "1"), 0);
	assert_int_equal(TRACE("out.json", "out.csv", "--threads", "1"), 0);
	assert_int_equal(alphas("stl.csv", a, s), 4);
	assert_int_equal(alphas("stl1.csv", c, u), 4);
	assert_int_equal(alphas("out.csv", b, t), 4);
	for (i = 1; i < 4; i++) {
		if (fabs(a[i] - b[i]) > 3.0 * hypot(s[i], t[i]) + 1e-12)
			fail_msg("row %d: %.6g +- %.2g STL, %.6g +- %.2g OBJ",
				 i, a[i], s[i], b[i], t[i]);
		differs |= fabs(c[i] - a[i]) > 3.0 * hypot(s[i], u[i]);
	}
	assert_true(differs);	/* the exterior's coating is used */
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_inward_turned_and_said),
		cmocka_unit_test(test_metres_refused_then_scaled),
		cmocka_unit_test(test_stl_parts_take_their_coatings),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
