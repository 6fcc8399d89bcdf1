/*
 * test_user_families.c - issue 23's "Done when": user designs unlike
 * ref4, three baffle families and two sensors of their own, through the
 * commands as a user runs them.
 *
 *   thin     6 vanes of 0.3 mm, 45 deg lower bevels, an 8 deg cone, 3 %
 *   bevel30  3 vanes of 1.5 mm, 30 deg upper bevels, a 10 deg cone, 6 %
 *   wide     4 vanes of 1 mm, 60 deg bevels, an 18 deg cone, 4 %
 *   sensors  1280 x 1024 (4.8 um, 12 deg) and 2048 x 2048 (5.5 um,
 *            18 deg, 0.2 s, 5 e- read noise)
 *
 * For each family: its vane JSON and its exported mesh (thin wound
 * inward, wide in metres with "scale_mm": 1000) trace the same curve
 * within 3 sigma; for each sensor, `exclusion`, `sweep` and
 * `firmware-table` give one Sun verdict (the same angle, or null all
 * three); and a coating and a knife edge hidden in a photometer's curve
 * are named by `diagnose` with intervals that hold them and the scene's
 * own nominal coating in its words.  Few rays: about 30 s in all.
 */
#include <cJSON.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "../scratch.h"
#include "../test_util.h"
#include "run_cli.h"

static struct cli_run r;
static char dir[] = "/tmp/stray_familiesXXXXXX";

#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })

struct family {
	const char *name, *json;
	double rho, edge;		/* the hidden truth of the lab curve */
	int reverse;			/* its mesh wound inward */
	double scale;			/* its mesh's file units per mm */
	double pupil_z, pupil_r;
};

static const struct family fam[] = {
	{ "thin", "{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 }, "
	  "{ \"z\": -6 }, { \"z\": -12 }, { \"z\": -18 }, { \"z\": -24 }, "
	  "{ \"z\": -30 } ], \"vane_thickness\": 0.3, \"bevel_angle_deg\": 45, "
	  "\"bevel_face\": \"lower\", \"cone_half_angle_deg\": 8, \"tube\": "
	  "{ \"inner_radius\": 14, \"wall\": 1 }, \"pupil\": { \"radius\": 4, "
	  "\"z\": -36 }, \"reflectance\": 0.03 }", 0.055, 0.06, 1, 1.0,
	  -36, 4 },
	{ "bevel30", "{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 }, "
	  "{ \"z\": -15 }, { \"z\": -30 } ], \"vane_thickness\": 1.5, "
	  "\"bevel_angle_deg\": 30, \"bevel_face\": \"upper\", "
	  "\"cone_half_angle_deg\": 10, \"tube\": { \"inner_radius\": 22, "
	  "\"wall\": 2 }, \"pupil\": { \"radius\": 7, \"z\": -42 }, "
	  "\"reflectance\": 0.06 }", 0.09, 0.15, 0, 1.0, -42, 7 },
	{ "wide", "{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0 }, "
	  "{ \"z\": -8 }, { \"z\": -16 }, { \"z\": -24 } ], "
	  "\"vane_thickness\": 1, \"bevel_angle_deg\": 60, \"bevel_face\": "
	  "\"lower\", \"cone_half_angle_deg\": 18, \"tube\": { \"inner_radius\": "
	  "24, \"wall\": 1.5 }, \"pupil\": { \"radius\": 6, \"z\": -30 }, "
	  "\"reflectance\": 0.04 }", 0.07, 0.1, 0, 1e-3, -30, 6 },
};

static const char *const sensors[2] = {
	"{ \"name\": \"user-1280\", \"pixels_x\": 1280, \"pixels_y\": 1024, "
	"\"pixel_pitch_um\": 4.8, \"aperture_diameter_mm\": 10, "
	"\"fov_half_deg\": 12, \"t_exp_s\": 0.1 }",
	"{ \"name\": \"wide-2048\", \"pixels_x\": 2048, \"pixels_y\": 2048, "
	"\"pixel_pitch_um\": 5.5, \"aperture_diameter_mm\": 14, "
	"\"fov_half_deg\": 18, \"t_exp_s\": 0.2, \"read_noise_e\": 5, "
	"\"drs_mag\": 5.5 }",
};

static char *at(const char *fmt, const char *name)
{
	static char p[16][256];
	static int k;
	char *s = p[k++ % 16], leaf[96];

	snprintf(leaf, sizeof(leaf), fmt, name);
	snprintf(s, 256, "%s/%s", dir, leaf);
	return s;
}

static void put(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static cJSON *out_json(void)
{
	cJSON *j = cJSON_Parse(r.out);

	if (!j)
		fail_msg("not JSON (status %d): %.300s / %.300s", r.status,
			 r.out, r.err);
	return j;
}

static void ok(void)
{
	if (r.status != 0)
		fail_msg("status %d: %.600s", r.status, r.err);
}

/* alpha and sigma of a curve CSV's rows. */
static int alphas(const char *path, double *a, double *s)
{
	FILE *f = fopen(path, "r");
	char line[512];
	int n = 0;

	assert_non_null(f);
	while (fgets(line, sizeof(line), f))
		if (line[0] != '#' && line[0] != 't' && n < 64 &&
		    sscanf(line, "%*f,%lf,%lf", &a[n], &s[n]) == 2)
			n++;
	fclose(f);
	return n;
}

/* The family's OBJ, rewritten as an exporter might have: faces
 * reversed, or vertices in other units. */
static void rewrite(const struct family *F, const char *in, const char *out)
{
	FILE *i = fopen(in, "r"), *o = fopen(out, "w");
	char line[256];

	assert_non_null(i);
	assert_non_null(o);
	while (fgets(line, sizeof(line), i)) {
		double x, y, z;
		long a, b, c;

		if (F->reverse && sscanf(line, "f %ld %ld %ld", &a, &b, &c) == 3)
			fprintf(o, "f %ld %ld %ld\n", a, c, b);
		else if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3)
			fprintf(o, "v %.9g %.9g %.9g\n", x * F->scale,
				y * F->scale, z * F->scale);
		else
			fputs(line, o);
	}
	fclose(i);
	fclose(o);
}

static int setup(void **state)
{
	(void)state;
	if (!mkdtemp(dir))
		return -1;
	put(at("%s", "s0.json"), sensors[0]);
	put(at("%s", "s1.json"), sensors[1]);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

#define ANGLES "0,5,10:90:2"

/* The vane file and the mesh a CAD tool gave of it: one curve. */
static void check_mesh(const struct family *F)
{
	char scene[1024];
	double a[64], s[64], b[64], t[64];
	int n, i;

	STRAY("trace", "--scene", at("%s.json", F->name), "--export-obj",
	      at("%s.obj", F->name));
	ok();
	rewrite(F, at("%s.obj", F->name), at("%s_cad.obj", F->name));
	snprintf(scene, sizeof(scene), "{ \"meshes\": [ { \"file\": "
		 "\"%s_cad.obj\", \"scale_mm\": %g } ], \"materials\": { "
		 "\"coat\": { \"type\": \"lambert\", \"reflectance\": %g }, "
		 "\"exterior\": { \"type\": \"mirror\", \"reflectance\": 1 }, "
		 "\"detector\": { \"type\": \"absorber\" } }, "
		 "\"default_material\": \"coat\", \"detector\": { \"shape\": "
		 "\"disk\", \"center\": [0, 0, %g], \"normal\": [0, 0, 1], "
		 "\"radius_mm\": %g }, \"beam\": { \"center\": [0, 0, 0], "
		 "\"radius_mm\": \"auto\" } }", F->name, 1.0 / F->scale,
		 !strcmp(F->name, "thin") ? 0.03 : !strcmp(F->name, "wide")
		 ? 0.04 : 0.06, F->pupil_z, F->pupil_r);
	put(at("%s_cad.json", F->name), scene);
	STRAY("trace", "--scene", at("%s_cad.json", F->name), "--angles",
	      ANGLES, "--rays", "30000", "--out", at("%s_cad.csv", F->name));
	ok();
	if (F->reverse && !strstr(r.err, "wound inward"))
		fail_msg("%s: the inward mesh was not said: %s", F->name, r.err);
	n = alphas(at("%s.csv", F->name), a, s);
	assert_int_equal(alphas(at("%s_cad.csv", F->name), b, t), n);
	for (i = 1; i < n; i++)
		if (fabs(a[i] - b[i]) > 3.0 * hypot(s[i], t[i]) + 1e-12)
			fail_msg("%s row %d: vane file %.4g +- %.2g, mesh %.4g "
				 "+- %.2g", F->name, i, a[i], s[i], b[i], t[i]);
}

/* One Sun verdict from exclusion, sweep and firmware-table. */
static void check_verdicts(const struct family *F, int k)
{
	char grid[64], *sensor = at("s%s.json", k ? "1" : "0");
	const cJSON *v[3];
	cJSON *j[3];
	int i;

	snprintf(grid, sizeof(grid), "reflectance=%g",
		 !strcmp(F->name, "thin") ? 0.03 : !strcmp(F->name, "wide")
		 ? 0.04 : 0.06);
	STRAY("exclusion", "--curve", at("%s.csv", F->name), "--sensor",
	      sensor, "--json");
	ok();
	j[0] = out_json();
	v[0] = cJSON_GetObjectItem(j[0], "sun_deg");
	STRAY("sweep", "--scene", at("%s.json", F->name), "--sensor", sensor,
	      "--grid", grid, "--rays", "30000", "--angles", ANGLES, "--state",
	      at("sw_%s", F->name), "--json");
	ok();
	j[1] = out_json();
	v[1] = cJSON_GetObjectItem(cJSON_GetArrayItem(
		cJSON_GetObjectItem(j[1], "designs"), 0), "sun_deg");
	STRAY("firmware-table", "--curve", at("%s.csv", F->name), "--sensor",
	      sensor, "--out-bin", at("%s.bin", F->name), "--json");
	ok();
	j[2] = out_json();
	v[2] = cJSON_GetObjectItem(j[2], "sun_deg");
	for (i = 1; i < 3; i++) {
		if (cJSON_IsNull(v[0]) != cJSON_IsNull(v[i]))
			fail_msg("%s/s%d: exclusion %s, %s %s", F->name, k,
				 cJSON_IsNull(v[0]) ? "null" : "an angle",
				 i == 1 ? "sweep" : "firmware-table",
				 cJSON_IsNull(v[i]) ? "null" : "an angle");
		if (!cJSON_IsNull(v[0]))	/* the table holds floats */
			assert_near(v[i]->valuedouble, v[0]->valuedouble, 1e-4);
	}
	for (i = 0; i < 3; i++)
		cJSON_Delete(j[i]);
	{
		char cmd[300];

		snprintf(cmd, sizeof(cmd), "rm -rf '%s'", at("sw_%s", F->name));
		assert_int_equal(system(cmd), 0);
	}
}

/* A lab curve with a coating and a knife edge the model is not told of:
 * both named, their intervals holding the truth, the scene's nominal. */
static void check_diagnosis(const struct family *F)
{
	char rho[32], edge[32], nominal[32];
	const cJSON *c;
	cJSON *j;
	int named = 0;

	snprintf(rho, sizeof(rho), "reflectance=%g", F->rho);
	snprintf(edge, sizeof(edge), "edge_radius=%g", F->edge);
	STRAY("trace", "--scene", at("%s.json", F->name), "--set", rho,
	      "--set", edge, "--rays", "150000", "--angles", "0,5,10,15,20,"
	      "25:88:3", "--out", at("%s_truth.csv", F->name));
	ok();
	STRAY("photometer", "--truth", at("%s_truth.csv", F->name), "--out",
	      at("%s_lab.csv", F->name), "--seed", "3");
	ok();
	STRAY("diagnose", at("%s_lab.csv", F->name), "--scene",
	      at("%s.json", F->name), "--sensor", at("%s", "s1.json"),
	      "--rays", "20000", "--causes",
	      "reflectance,knife_edge_radius,floor", "--json");
	ok();
	j = out_json();
	cJSON_ArrayForEach(c, cJSON_GetObjectItem(j, "causes")) {
		const char *name = cJSON_GetObjectItem(c, "name")->valuestring;
		const char *key = !strcmp(name, "reflectance") ? "reflectance"
			: !strcmp(name, "knife_edge_radius") ? "radius_mm" : NULL;
		double truth = key && key[0] == 'r' && key[1] == 'e' ? F->rho
							      : F->edge;
		const cJSON *iv;

		if (!key)
			continue;
		iv = cJSON_GetObjectItem(cJSON_GetObjectItem(c, "intervals"),
					 key);
		if (!cJSON_IsArray(iv) ||
		    !(cJSON_GetArrayItem(iv, 0)->valuedouble <= truth &&
		      truth <= cJSON_GetArrayItem(iv, 1)->valuedouble))
			fail_msg("%s: %s interval misses %g: %.400s", F->name,
				 name, truth, cJSON_Print(c));
		named++;
	}
	if (named != 2)
		fail_msg("%s: %d of the 2 hidden causes named: %.600s",
			 F->name, named, r.out);
	cJSON_Delete(j);
	STRAY("diagnose", at("%s_lab.csv", F->name), "--scene",
	      at("%s.json", F->name), "--sensor", at("%s", "s1.json"),
	      "--rays", "20000", "--causes",
	      "reflectance,knife_edge_radius,floor");
	ok();
	snprintf(nominal, sizeof(nominal), "(nominal %g)",
		 !strcmp(F->name, "thin") ? 0.03 : !strcmp(F->name, "wide")
		 ? 0.04 : 0.06);
	if (!strstr(r.out, nominal) || !strstr(r.out, "In orbit (wide-2048"))
		fail_msg("%s: the words lack '%s' or the sensor: %.900s",
			 F->name, nominal, r.out);
}

static void run_family(int i)
{
	const struct family *F = &fam[i];

	put(at("%s.json", F->name), F->json);
	STRAY("trace", "--scene", at("%s.json", F->name), "--angles", ANGLES,
	      "--rays", "30000", "--out", at("%s.csv", F->name));
	ok();
	check_mesh(F);
	check_verdicts(F, 0);
	check_verdicts(F, 1);
	check_diagnosis(F);
}

static void test_thin(void **state) { (void)state; run_family(0); }
static void test_bevel30(void **state) { (void)state; run_family(1); }
static void test_wide(void **state) { (void)state; run_family(2); }

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_thin),
		cmocka_unit_test(test_bevel30),
		cmocka_unit_test(test_wide),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
