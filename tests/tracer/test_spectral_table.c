/*
 * test_spectral_table.c - issue 17 item 5: a coating whose reflectance
 * changes with wavelength ("reflectance_table" in a scene file) traced
 * under the Sun x QE band.  Each photon keeps its wavelength, so a
 * two-band coating (rho_a below 655 nm, rho_b above) must give exactly
 * the photon-weighted mixture of two grey traces,
 *   P(theta) = w_a P_grey(rho_a) + w_b P_grey(rho_b),
 * with w_a from this test's own 1 nm integration of the built-in spectra,
 * and differ from a grey trace at the band-mean reflectance where
 * second-order scatter dominates (<rho^2> > <rho>^2).  Bad tables are
 * refused naming the field.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../scratch.h"
#include "stray/photometry.h"
#include "stray/spectrum_io.h"
#include "tracer/integrator.h"
#include "tracer/obj_export.h"
#include "tracer/scene_load.h"
#include "tracer/spectral.h"

#define RHO_A 0.02
#define RHO_B 0.10
#define SPLIT_NM 655.0
#define N_TH 4

static const double theta[N_TH] = { 0.0, 35.0, 45.0, 60.0 };
static char dir[] = "/tmp/stray_spec_XXXXXX";
static struct tracer_scene ref4;

static void write_scene(const char *name, const char *black)
{
	char path[256];
	FILE *f;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	f = fopen(path, "w");
	assert_non_null(f);
	fprintf(f, "{ \"meshes\": [ { \"file\": \"ref4.obj\" } ],\n"
		"  \"materials\": { \"black\": %s,\n"
		"    \"shiny\": { \"type\": \"mirror\", \"reflectance\": %.17g },\n"
		"    \"dead\": { \"type\": \"absorber\" } },\n"
		"  \"groups\": { \"exterior\": \"shiny\", \"detector\": \"dead\" },\n"
		"  \"default_material\": \"black\",\n"
		"  \"detector\": { \"shape\": \"disk\", \"center\": [%.17g, %.17g, %.17g],\n"
		"    \"normal\": [%.17g, %.17g, %.17g], \"radius_mm\": %.17g,\n"
		"    \"accept_half_angle_deg\": %.17g },\n"
		"  \"beam\": { \"center\": [%.17g, %.17g, %.17g],\n"
		"    \"normal\": [%.17g, %.17g, %.17g], \"radius_mm\": %.17g } }\n",
		black, ref4.material[1].rho,
		ref4.det.center.x, ref4.det.center.y, ref4.det.center.z,
		ref4.det.normal.x, ref4.det.normal.y, ref4.det.normal.z,
		ref4.det.radius_mm, ref4.det.accept_half_angle_deg,
		ref4.beam.center.x, ref4.beam.center.y, ref4.beam.center.z,
		ref4.beam.normal.x, ref4.beam.normal.y, ref4.beam.normal.z,
		ref4.beam.radius_mm);
	fclose(f);
}

static int setup(void **state)
{
	struct stray_error err;
	char path[256];
	size_t g;

	(void)state;
	if (!mkdtemp(dir))
		return -1;
	stray_error_clear(&err);
	tracer_scene_init(&ref4);
	if (tracer_scene_load("ref4", NULL, 0, &ref4, &err))
		return -1;
	for (g = 0; g < ref4.mesh.n_group; g++)	/* the mirror's rho at [1] */
		if (strcmp(ref4.mesh.group_name[g], "exterior") == 0)
			ref4.material[1].rho = ref4.material[g].rho;
	snprintf(path, sizeof(path), "%s/ref4.obj", dir);
	return tracer_obj_export(&ref4.mesh, path, &err);
}

static int teardown(void **state)
{
	(void)state;
	tracer_scene_free(&ref4);
	return scratch_remove(dir);
}

/* Power and sigma at each angle of a scene file (band-weighted when it
 * has a table). */
static void trace(const char *name, double *p, double *sg)
{
	struct tracer_scene s;
	struct tracer_trace_opts o;
	struct tracer_result r;
	struct tracer_band band;
	struct stray_error err;
	char path[256];
	size_t j;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	stray_error_clear(&err);
	tracer_scene_init(&s);
	memset(&r, 0, sizeof(r));
	assert_int_equal(tracer_scene_load(path, NULL, 0, &s, &err), 0);
	assert_int_equal(tracer_scene_commit(&s, &err), 0);
	tracer_trace_defaults(&o);
	o.theta_deg = theta;
	o.n_theta = N_TH;
	o.n_paths = 200000;
	o.seed = 7;
	o.threads = 2;
	o.record_paths = tracer_scene_spectral(&s);
	assert_int_equal(tracer_trace(&s, &o, &r, &err), 0);
	if (tracer_scene_spectral(&s)) {
		assert_int_equal(tracer_band_load(NULL, NULL, &band, &err), 0);
		assert_int_equal(tracer_result_apply_band(&r, &s, &band, &err),
				 0);
	}
	for (j = 0; j < N_TH; j++)
		tracer_result_power(&r, j, -1, &p[j], &sg[j]);
	tracer_result_free(&r);
	tracer_scene_free(&s);
}

/* The band's photon weight below SPLIT_NM, by this test's own 1 nm sum. */
static double blue_weight(void)
{
	struct stray_spectrum_data sun, qe;
	struct stray_error err;
	double l, a = 0.0, all = 0.0;

	memset(&sun, 0, sizeof(sun));
	memset(&qe, 0, sizeof(qe));
	stray_error_clear(&err);
	assert_int_equal(stray_spectrum_load("builtin:sun_am0_astm_e490", &sun,
					     &err), 0);
	assert_int_equal(stray_spectrum_load("builtin:qe_mt9p031_approx", &qe,
					     &err), 0);
	for (l = 300.0; l <= 1200.0; l += 1.0) {
		double w = stray_spectrum_at(&sun.s, l) *
			   stray_spectrum_at(&qe.s, l) * l;

		all += w;
		if (l < SPLIT_NM)
			a += w;
	}
	stray_spectrum_data_free(&sun);
	stray_spectrum_data_free(&qe);
	return a / all;
}

static void test_two_band_is_the_photon_mixture(void **state)
{
	double ps[N_TH], ss[N_TH], pa[N_TH], sa[N_TH], pb[N_TH], sb[N_TH];
	double pm[N_TH], sm[N_TH], wa = blue_weight(), mean;
	char black[256];
	size_t j;
	int differs = 0;

	(void)state;
	snprintf(black, sizeof(black), "{ \"type\": \"lambert\", "
		 "\"reflectance_table\": { \"wavelength_nm\": [300, %g, %g, "
		 "1200], \"reflectance\": [%g, %g, %g, %g] } }",
		 SPLIT_NM - 1.0, SPLIT_NM + 1.0, RHO_A, RHO_A, RHO_B, RHO_B);
	write_scene("two_band.json", black);
	snprintf(black, sizeof(black), "{ \"type\": \"lambert\", "
		 "\"reflectance\": %g }", RHO_A);
	write_scene("grey_a.json", black);
	snprintf(black, sizeof(black), "{ \"type\": \"lambert\", "
		 "\"reflectance\": %g }", RHO_B);
	write_scene("grey_b.json", black);
	mean = wa * RHO_A + (1.0 - wa) * RHO_B;
	snprintf(black, sizeof(black), "{ \"type\": \"lambert\", "
		 "\"reflectance\": %.17g }", mean);
	write_scene("grey_mean.json", black);
	trace("two_band.json", ps, ss);
	trace("grey_a.json", pa, sa);
	trace("grey_b.json", pb, sb);
	trace("grey_mean.json", pm, sm);
	fprintf(stderr, "blue weight %.4f, band-mean rho %.4f\n", wa, mean);
	for (j = 1; j < N_TH; j++) {
		double mix = wa * pa[j] + (1.0 - wa) * pb[j];
		double smix = hypot(wa * sa[j], (1.0 - wa) * sb[j]);
		double tol = 3.0 * hypot(ss[j], smix) + 0.01 * mix;

		fprintf(stderr, "theta %g: spectral %.4g +- %.2g, mixture "
			"%.4g +- %.2g, grey at band mean %.4g +- %.2g\n",
			theta[j], ps[j], ss[j], mix, smix, pm[j], sm[j]);
		assert_true(fabs(ps[j] - mix) < tol);
		if (ps[j] - pm[j] > 3.0 * hypot(ss[j], sm[j]))
			differs++;
	}
	assert_true(differs >= 1);	/* not the band mean to the power k */
}

static void expect_bad(const char *black, const char *field)
{
	struct tracer_scene s;
	struct stray_error err;
	char path[256];

	write_scene("bad.json", black);
	snprintf(path, sizeof(path), "%s/bad.json", dir);
	stray_error_clear(&err);
	tracer_scene_init(&s);
	assert_int_not_equal(tracer_scene_load(path, NULL, 0, &s, &err), 0);
	tracer_scene_free(&s);
	if (!(err.field && strstr(err.field, field)) &&
	    !strstr(err.file, field))
		fail_msg("error (field '%s', file '%s') lacks '%s'",
			 err.field ? err.field : "", err.file, field);
}

static void test_bad_tables_named(void **state)
{
	(void)state;
	expect_bad("{ \"type\": \"lambert\", \"reflectance_table\": "
		   "{ \"wavelength_nm\": [500, 400], \"reflectance\": [0.1, 0.1] } }",
		   "reflectance_table");
	expect_bad("{ \"type\": \"lambert\", \"reflectance_table\": "
		   "{ \"wavelength_nm\": [400, 500], \"reflectance\": [0.1, 1.5] } }",
		   "reflectance_table");
	expect_bad("{ \"type\": \"lambert\", \"reflectance_table\": "
		   "{ \"wavelength_nm\": [400, 500], \"reflectance\": [0.1] } }",
		   "reflectance_table");
	expect_bad("{ \"type\": \"lambert\", \"reflectance_table\": "
		   "\"missing.csv\" }", "missing.csv");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_band_is_the_photon_mixture),
		cmocka_unit_test(test_bad_tables_named),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
