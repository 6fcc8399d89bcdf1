/*
 * test_angles_auto.c - the default grid fitted to the scene (issue 23
 * item 5): its direct cut-off against the closed form of a single thin
 * aperture over a detector disk, theta_c = atan((R + r) / L); on ref4
 * and a narrow baffle, a superset of the old fixed grid, 0.1 deg steps
 * around the cut-off, and a traced direct term that is zero beyond it
 * and not before.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../scratch.h"
#include "tracer_test.h"
#include "tracer/angles.h"
#include "tracer/integrator.h"
#include "tracer/scene_load.h"

const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
	return "leak:libassimp.so\n";
}

static char dir[] = "/tmp/tracer_autoXXXXXX";

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

static void load_text(const char *text, struct tracer_scene *s)
{
	char path[256];
	struct stray_error err;
	FILE *f;

	snprintf(path, sizeof(path), "%s/scene.json", dir);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
	stray_error_clear(&err);
	tracer_scene_init(s);
	if (tracer_scene_load(path, NULL, 0, s, &err))
		fail_msg("%s %s", err.field ? err.field : "",
			 err.reason ? err.reason : "");
	assert_int_equal(tracer_scene_commit(s, NULL), 0);
}

static size_t count_within(const double *t, size_t n, double lo, double hi)
{
	size_t i, k = 0;

	for (i = 0; i < n; i++)
		k += t[i] >= lo && t[i] <= hi;
	return k;
}

/* One square-edged aperture R = 5 mm, 20 mm over a pupil of r = 3 mm:
 * the last direct ray leaves the pupil's far rim through the aperture's
 * far rim, tan theta_c = (R + r) / L = 8 / 20 (21.80 deg).  The grid's
 * detector points sit inside the rim (the outermost ring at about 0.99 r),
 * so the estimate may fall short by up to 0.2 deg, never beyond. */
static void test_auto_cutoff_closed_form(void **state)
{
	struct tracer_scene s;
	double *t, cut, want = atan(8.0 / 20.0) * 180.0 / M_PI;
	size_t n;

	(void)state;
	load_text("{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0, "
		  "\"aperture_mm\": 5 } ], \"vane_thickness\": 0.02, "
		  "\"bevel_angle_deg\": 90, \"pupil\": { \"radius\": 3, "
		  "\"z\": -20 }, \"tube\": { \"inner_radius\": 20, "
		  "\"wall\": 1 } }", &s);
	assert_int_equal(tracer_angles_auto(&s, &t, &n, &cut, NULL), 0);
	if (!(cut > want - 0.2 && cut <= want + 0.1))
		fail_msg("cut-off %.2f deg, closed form %.2f", cut, want);
	/* 0.1 deg steps within a degree of it: 21 angles */
	assert_true(count_within(t, n, cut - 1.0 - 1e-9, cut + 1.0 + 1e-9) >= 20);
	free(t);
	tracer_scene_free(&s);
}

/* ref4 and a narrow 3-vane baffle: every angle of the fixed grid is kept,
 * and the trace's own direct term ends where the grid says. */
static void check_scene(struct tracer_scene *s, double lo, double hi)
{
	double *t, *fixed, cut;
	size_t n, nf, i, j;
	struct tracer_trace_opts o;
	struct tracer_result r;
	double before = 0, after = 0;

	assert_int_equal(tracer_angles_auto(s, &t, &n, &cut, NULL), 0);
	if (!(cut > lo && cut < hi))
		fail_msg("cut-off %.2f deg not in (%g, %g)", cut, lo, hi);
	assert_int_equal(tracer_angles_parse(TRACER_ANGLES_DEFAULT, &fixed,
					     &nf, NULL), 0);
	for (i = 0, j = 0; i < nf; i++) {
		while (j < n && t[j] < fixed[i] - 1e-9)
			j++;
		if (j == n || fabs(t[j] - fixed[i]) > 1e-9)
			fail_msg("fixed-grid angle %g missing", fixed[i]);
	}
	for (i = 1; i < n; i++)
		assert_true(t[i] > t[i - 1]);
	/* the direct term: > 0 at cut - 0.3 deg, exactly 0 at cut + 0.1 */
	tracer_trace_defaults(&o);
	o.n_paths = 40000;
	o.threads = 1;
	o.theta_deg = (double[]){ 0.0, cut - 0.3, cut + 0.1 };
	o.n_theta = 3;
	assert_int_equal(tracer_trace(s, &o, &r, NULL), 0);
	{
		double p, sg;

		tracer_result_power(&r, 1, 0, &p, &sg);
		before = p;
		tracer_result_power(&r, 2, 0, &p, &sg);
		after = p;
	}
	if (!(before > 0.0 && after == 0.0))
		fail_msg("direct power %g at %.1f deg, %g at %.1f deg", before,
			 cut - 0.3, after, cut + 0.1);
	tracer_result_free(&r);
	free(fixed);
	free(t);
}

static void test_auto_ref4_and_narrow(void **state)
{
	struct tracer_scene s;

	(void)state;
	tracer_scene_init(&s);
	assert_int_equal(tracer_scene_load("ref4", NULL, 0, &s, NULL), 0);
	assert_int_equal(tracer_scene_commit(&s, NULL), 0);
	check_scene(&s, 20.0, 30.0);
	tracer_scene_free(&s);
	/* 3 thin vanes with 4 mm apertures over a 2 mm pupil: cut-off
	 * between 5-deg steps of the old grid */
	load_text("{ \"type\": \"vanes\", \"vanes\": [ { \"z\": 0, "
		  "\"aperture_mm\": 4 }, { \"z\": -12, \"aperture_mm\": 3.5 }, "
		  "{ \"z\": -24, \"aperture_mm\": 3 } ], \"vane_thickness\": "
		  "0.5, \"pupil\": { \"radius\": 2, \"z\": -36 }, "
		  "\"reflectance\": 0.05 }", &s);
	check_scene(&s, 5.0, 15.0);
	tracer_scene_free(&s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_auto_cutoff_closed_form),
		cmocka_unit_test(test_auto_ref4_and_narrow),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
