/*
 * trace_run.c - the default trace: this process's threads (trace_run.h).
 */
#include <math.h>
#include <unistd.h>

#include "cli.h"
#include "trace_run.h"

static int trace_local(const struct trace_scene_spec *spec,
		       const struct tracer_scene *s,
		       const struct tracer_trace_opts *o,
		       struct tracer_result *res, struct stray_error *err)
{
	(void)spec;
	return tracer_trace(s, o, res, err);
}

trace_run_fn trace_run = trace_local;

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

void trace_scene_edit(const struct trace_scene_spec *spec,
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
	if (spec->beam_shift_z != 0.0)	/* beam axis through the pivot */
		s->beam.center.z -= spec->beam_shift_z;
}

void trace_run_defaults(struct tracer_trace_opts *o, uint64_t n_paths)
{
	long ncpu = sysconf(_SC_NPROCESSORS_ONLN);

	tracer_trace_defaults(o);
	o->n_paths = n_paths;
	o->threads = ncpu > 0 && ncpu <= 256 ? (int)ncpu : 1;
}

int trace_run_option(const char *cmd, int opt, const char *text,
		     struct tracer_trace_opts *o, int *rc)
{
	double v = 0.0;

	switch (opt) {
	case 'n': *rc = cli_parse_count(cmd, "rays", text, 2, 1e12, &v);
		o->n_paths = (uint64_t)v; return 0;
	case 'k': *rc = cli_parse_count(cmd, "seed", text, 0, 9e15, &v);
		o->seed = (uint64_t)v; return 0;
	case 't': *rc = cli_parse_count(cmd, "threads", text, 1, 256, &v);
		o->threads = (int)v; return 0;
	case 'b': *rc = cli_parse_count(cmd, "batches", text, 2, 4096, &v);
		o->n_batches = (int)v; return 0;
	default:
		return 1;
	}
}
