/*
 * surfaces_model.c - the extended model of the surface at fault
 * (surfaces.c): the scene with the fitted factors written as a JSON scene
 * file (tracer/scene_file.c) with its mesh as OBJ, and confirmed by
 * tracing that file.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "diagnose/diag_fit.h"
#include "diagnose/diag_result.h"
#include "diagnose/diag_surfaces.h"
#include "path_rows.h"
#include "surfaces.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/integrator.h"
#include "tracer/obj_export.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

static double factor_of(const struct diag_surfaces *s, int group)
{
	int k;

	for (k = 0; k < s->n_named; k++)
		if (s->group[s->named[k]] == group)
			return pow(10.0, s->log10_f[k]);
	return 1.0;
}

static void write_vec(FILE *f, const char *key, struct vec3 v)
{
	fprintf(f, "\"%s\": [%.17g, %.17g, %.17g]", key, v.x, v.y, v.z);
}

static void write_material(FILE *f, const struct tracer_brdf *m, double fac)
{
	if (!m->ops)
		fprintf(f, "{ \"type\": \"absorber\" }");
	else if (m->ops == &tracer_brdf_mirror_ops)
		fprintf(f, "{ \"type\": \"mirror\", \"reflectance\": %.17g }",
			m->rho);
	else if (m->ops == &tracer_brdf_abg_ops)
		fprintf(f, "{ \"type\": \"abg\", \"reflectance\": %.17g, "
			"\"a\": %.17g, \"b\": %.17g, \"g\": %.17g }",
			m->rho, m->abg.a * fac, m->abg.b, m->abg.g);
	else
		fprintf(f, "{ \"type\": \"lambert\", \"reflectance\": %.17g }",
			fmin(m->rho * fac, 1.0));
}

/* The mesh as OBJ, written in place (the confirmation's private copy;
 * the user's copy goes through tracer_obj_export, with the run's other
 * outputs). */
static int obj_in_place(const struct tracer_mesh *m, const char *path,
			struct stray_error *err)
{
	FILE *f = fopen(path, "w");
	size_t i, g;

	if (!f)
		return stray_error_set(err, STRAY_EIO, "diagnose",
				       "cannot write the model's mesh");
	for (i = 0; i < m->n_vert; i++)
		fprintf(f, "v %.9g %.9g %.9g\n", m->vert[3 * i],
			m->vert[3 * i + 1], m->vert[3 * i + 2]);
	for (g = 0; g < m->n_group; g++) {
		fprintf(f, "g %s\n", m->group_name[g]);
		for (i = 0; i < m->n_tri; i++)
			if (m->group[i] == g)
				fprintf(f, "f %u %u %u\n", m->tri[3 * i] + 1,
					m->tri[3 * i + 1] + 1,
					m->tri[3 * i + 2] + 1);
	}
	return fclose(f) == 0 ? STRAY_OK :
		stray_error_set(err, STRAY_EIO, "diagnose",
				"cannot write the model's mesh");
}

static void write_scene_json(FILE *f, const struct diag_eval *e,
			     const struct diag_surfaces *s,
			     const struct tracer_scene *sc, const char *obj)
{
	const struct tracer_detector *d = &sc->det;
	size_t g;

	fprintf(f, "{\n  \"comment\": \"stray diagnose --write-model: "
		"%s with %d surface group(s) changed\",\n", e->scene,
		s->n_named);
	fprintf(f, "  \"meshes\": [ { \"file\": \"%s\" } ],\n", obj);
	fprintf(f, "  \"materials\": {\n");
	for (g = 0; g < sc->mesh.n_group; g++) {
		fprintf(f, "    \"%s\": ", sc->mesh.group_name[g]);
		write_material(f, &sc->material[g], factor_of(s, (int)g));
		fprintf(f, "%s\n", g + 1 < sc->mesh.n_group ? "," : "");
	}
	fprintf(f, "  },\n  \"detector\": { \"shape\": \"%s\", ",
		d->shape == TRACER_DET_RECT ? "rect" : "disk");
	write_vec(f, "center", d->center);
	fprintf(f, ", ");
	write_vec(f, "normal", d->normal);
	if (d->shape == TRACER_DET_RECT)
		fprintf(f, ", \"width_mm\": %.17g, \"height_mm\": %.17g",
			2.0 * d->half_w_mm, 2.0 * d->half_h_mm);
	else
		fprintf(f, ", \"radius_mm\": %.17g", d->radius_mm);
	if (d->accept_half_angle_deg > 0.0)
		fprintf(f, ", \"accept_half_angle_deg\": %.17g",
			d->accept_half_angle_deg);
	fprintf(f, " },\n  \"beam\": { ");
	write_vec(f, "center", sc->beam.center);
	fprintf(f, ", ");
	write_vec(f, "normal", sc->beam.normal);
	fprintf(f, ", \"radius_mm\": %.17g }\n}\n", sc->beam.radius_mm);
}

/* in_place: plain stdio (readable at once); else the atomic writer
 * (renamed into place with the run's other outputs). */
static int write_model(const struct diag_eval *e,
		       const struct diag_surfaces *s, const char *path,
		       int in_place, struct stray_error *err)
{
	struct tracer_scene sc;
	struct stray_file_out out;
	char obj[4096];
	const char *base, *dot;
	size_t len = strlen(path);
	FILE *f = NULL;
	int rc;

	dot = strrchr(path, '.');
	if (!dot || strchr(dot, '/'))
		dot = path + len;
	if ((size_t)(dot - path) + 5 > sizeof(obj))
		return stray_error_set(err, STRAY_EINVAL, "--write-model",
				       "path too long");
	snprintf(obj, sizeof(obj), "%.*s.obj", (int)(dot - path), path);
	base = strrchr(obj, '/');
	base = base ? base + 1 : obj;
	tracer_scene_init(&sc);
	rc = tracer_scene_load(e->scene, e->sets, e->n_sets, &sc, err);
	if (!rc)
		rc = in_place ? obj_in_place(&sc.mesh, obj, err) :
			tracer_obj_export(&sc.mesh, obj, err);
	if (!rc && in_place && !(f = fopen(path, "w")))
		rc = stray_error_set(err, STRAY_EIO, "--write-model",
				     "cannot open for writing");
	if (!rc && !in_place) {
		rc = stray_file_open_atomic(&out, path, err);
		f = out.f;
	}
	if (!rc) {
		write_scene_json(f, e, s, &sc, base);
		if (in_place)
			rc = fclose(f) == 0 ? STRAY_OK :
				stray_error_set(err, STRAY_EIO,
						"--write-model", "write failed");
		else
			rc = stray_file_commit(&out, err);
	}
	tracer_scene_free(&sc);
	return rc;
}

int diag_surfaces_write_model(const struct diag_eval *e,
			      const struct diag_surfaces *s, const char *path,
			      struct stray_error *err)
{
	return write_model(e, s, path, 0, err);
}

int diag_surfaces_confirm(struct diag_eval *e, const struct diag_data *d,
			  struct diag_surfaces *s, struct stray_error *err)
{
	char dir[] = "/tmp/stray_model_XXXXXX", model_path[64], obj[64];
	struct diag_surf_table t;
	struct tracer_scene sc;
	struct tracer_result r;
	double chi2 = 0.0, rs = 0.0, a0, s0;
	size_t i, m = 0;
	int rc;

	memset(&t, 0, sizeof(t));
	memset(&r, 0, sizeof(r));
	tracer_scene_init(&sc);
	if (!mkdtemp(dir))
		return stray_error_set(err, STRAY_EIO, "diagnose",
				       "no temporary directory for the model");
	snprintf(model_path, sizeof(model_path), "%s/model.json", dir);
	snprintf(obj, sizeof(obj), "%s/model.obj", dir);
	t.theta = diag_surf_angles(e, &t.n_theta);
	rc = t.theta ? write_model(e, s, model_path, 1, err) : stray_error_set(err, STRAY_ENOMEM,
				"diagnose", "out of memory");
	if (!rc)
		rc = diag_surf_trace_scene(e, model_path, NULL, 0, 0, t.theta, t.n_theta, &r,
			 &sc, err);
	if (!rc) {
		e->trace_seconds += r.seconds;
		e->n_traces++;
		tracer_result_alpha(&r, 0, 0, -1, &a0, &s0);
		for (i = 0; i < d->n; i++) {
			double a, sa, l, sr;

			if (d->theta_deg[i] == 0.0)
				continue;
			tracer_result_alpha(&r, diag_surf_find_theta(&t, d->theta_deg[i]),
					    0, -1, &a, &sa);
			a *= s->base ? s->base[i] : 1.0;
			a = a > 1e-30 ? a : 1e-30;
			l = log10(d->alpha[i] / a);
			sr = sqrt(pow(d->sigma[i] / d->alpha[i], 2) +
				  pow(sa / a, 2)) / M_LN10;
			chi2 += (l / sr) * (l / sr);
			rs += l * l;
			m++;
		}
		s->chi2_retrace = chi2;
		s->rms_retrace = m ? sqrt(rs / m) : 0.0;
	}
	tracer_result_free(&r);
	tracer_scene_free(&sc);
	free(t.theta);
	unlink(model_path);
	unlink(obj);
	rmdir(dir);
	return rc;
}
