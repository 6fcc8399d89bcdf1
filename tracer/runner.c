/*
 * runner.c - the in-process runner and the scene edits a scene
 * description carries (runner.h).
 */
#include <math.h>

#include "tracer/brdf.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

static int run_local(void *ctx, const struct tracer_scene_spec *spec,
		     const struct tracer_scene *s,
		     const struct tracer_trace_opts *o,
		     struct tracer_result *res, struct stray_error *err)
{
	(void)ctx;
	(void)spec;
	return tracer_trace(s, o, res, err);
}

const struct tracer_runner tracer_runner_local = { run_local, NULL, NULL };

int tracer_run(const struct tracer_runner *r,
	       const struct tracer_scene_spec *spec,
	       const struct tracer_scene *s, const struct tracer_trace_opts *o,
	       struct tracer_result *res, struct stray_error *err)
{
	return r->run(r->ctx, spec, s, o, res, err);
}

/* One item: its scene built from the description, traced, handed on. */
static int run_item(const struct tracer_runner *r,
		    const struct tracer_trace_item *it, size_t i,
		    tracer_item_done_fn done, void *user,
		    struct stray_error *err)
{
	struct tracer_scene s;
	struct tracer_result res;
	int rc;

	tracer_scene_init(&s);
	rc = tracer_scene_load(it->spec.scene, it->spec.sets,
			       it->spec.n_sets, &s, err);
	if (!rc) {
		tracer_scene_spec_edit(&it->spec, &s);
		rc = tracer_scene_commit(&s, err);
	}
	if (!rc)
		rc = tracer_run(r, &it->spec, &s, it->o, &res, err);
	tracer_scene_free(&s);
	if (rc)
		return rc;
	rc = done(user, i, &res, err);
	tracer_result_free(&res);
	return rc;
}

int tracer_run_set(const struct tracer_runner *r,
		   const struct tracer_trace_item *items, size_t n,
		   tracer_item_done_fn done, void *user,
		   struct stray_error *err)
{
	size_t i;
	int rc = STRAY_OK;

	if (r->run_set)
		return r->run_set(r->ctx, items, n, done, user, err);
	for (i = 0; !rc && i < n; i++)
		rc = run_item(r, &items[i], i, done, user, err);
	return rc;
}

#ifndef M_PI	/* math.h hides it under strict C99 */
#define M_PI 3.14159265358979323846
#endif
#define ABG_B 0.01	/* knee of the ABg lobe (diagnose/cause_abg_scatter.c) */

/* A so that the normal-incidence integrated scatter of A/(B + r^g) over
 * the unit beta disk is 1 (cos(theta) d omega = d beta), so rho stays the
 * hemispherical reflectance: 1 / (2 pi int_0^1 r / (B + r^g) dr). */
static double abg_norm(double g)
{
	double sum = 0.0;
	int i, n = 4000;

	for (i = 0; i < n; i++) {	/* midpoint rule, smooth integrand */
		double r = (i + 0.5) / n;

		sum += r / (ABG_B + pow(r, g));
	}
	return 1.0 / (2.0 * M_PI * sum / n);
}

void tracer_scene_spec_edit(const struct tracer_scene_spec *spec,
			    struct tracer_scene *s)
{
	size_t k;

	if (spec->abg_g > 0.0) {
		double a = abg_norm(spec->abg_g);

		for (k = 0; k < s->mesh.n_group; k++)
			if (s->material[k].ops == &tracer_brdf_lambert_ops) {
				s->material[k].ops = &tracer_brdf_abg_ops;
				s->material[k].abg.a = a;
				s->material[k].abg.b = ABG_B;
				s->material[k].abg.g = spec->abg_g;
			}
	}
	/* beam axis through the pivot, behind the aperture along its
	 * normal (z for the vane family: the same bits as a z shift) */
	if (spec->beam_shift_z != 0.0)
		s->beam.center = v3_sub(s->beam.center,
			v3_scale(s->beam.normal, spec->beam_shift_z));
}
