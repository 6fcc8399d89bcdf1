/*
 * scene_json.c - what the scene-file readers (scene_file.c, the meshes;
 * scene_vanes.c, the vane family) share (scene_json.h): errors naming
 * the file and field, numbers, paths beside the scene file, and the
 * material objects with their reflectance tables.
 */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>

#include "stray/errfmt.h"
#include "stray/spectrum_io.h"
#include "scene_json.h"

#define ctx tracer_json_ctx

static int fail(const struct ctx *c, int code, const char *field,
		const char *reason)
{
	return stray_error_at(c->err, code, c->path, 0, field, reason);
}

int tracer_json_fail(const struct ctx *c, int code, const char *field,
		     const char *reason)
{
	return fail(c, code, field, reason);
}

int tracer_json_fail_text(const struct ctx *c, int code, const char *field,
			  const char *reason, const char *text)
{
	int rc = fail(c, code, field, reason);

	stray_error_text(c->err, text);
	return rc;
}

int tracer_json_number(const struct ctx *c, const cJSON *o, const char *key,
		       double *v, int required)
{
	const cJSON *it = cJSON_GetObjectItemCaseSensitive(o, key);

	if (!it && !required)
		return STRAY_OK;
	if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble))
		return fail(c, STRAY_EINVAL, key, it ? "must be a number" :
						   "is missing");
	*v = it->valuedouble;
	return STRAY_OK;
}

/* Path of a mesh file relative to the scene file's directory. */
void tracer_json_sibling(const char *scene, const char *file, char *out,
			 size_t size)
{
	const char *slash = strrchr(scene, '/');

	if (file[0] == '/' || !slash)
		snprintf(out, size, "%s", file);
	else
		snprintf(out, size, "%.*s/%s", (int)(slash - scene), scene,
			 file);
}

/* "reflectance_table": a CSV (wavelength_nm,<reflectance>) or inline
 * arrays; rho in [0, 1], wavelengths increasing; b->rho its mean. */
static int rho_table(const struct ctx *c, const cJSON *m,
		     struct tracer_brdf *b, struct tracer_rho_table *t)
{
	const cJSON *it = cJSON_GetObjectItemCaseSensitive(m,
							   "reflectance_table");
	double sum = 0.0;
	int i, n;

	t->n = 0;
	if (!it)
		return STRAY_OK;
	if (cJSON_IsString(it)) {
		struct stray_spectrum_data d;
		char path[PATH_MAX];
		int rc;

		tracer_json_sibling(c->path, it->valuestring, path, sizeof(path));
		memset(&d, 0, sizeof(d));
		rc = stray_spectrum_load(path, &d, c->err);
		if (!rc && (d.s.n < 1 || d.s.n > TRACER_RHO_TABLE_MAX))
			rc = fail(c, STRAY_EINVAL, "reflectance_table",
				  "needs 1 to 64 rows");
		for (i = 0; !rc && i < (int)d.s.n; i++) {
			t->nm[i] = d.wavelength_nm[i];
			t->rho[i] = d.value[i];
		}
		n = rc ? 0 : (int)d.s.n;
		stray_spectrum_data_free(&d);
		if (rc)
			return rc;
	} else {
		const cJSON *l = cJSON_GetObjectItemCaseSensitive(it,
							"wavelength_nm");
		const cJSON *r = cJSON_GetObjectItemCaseSensitive(it,
							"reflectance");

		n = cJSON_GetArraySize(l);
		if (!cJSON_IsArray(l) || !cJSON_IsArray(r) || n < 1 ||
		    n > TRACER_RHO_TABLE_MAX || cJSON_GetArraySize(r) != n)
			return fail(c, STRAY_EINVAL, "reflectance_table",
				    "must be a CSV file or { \"wavelength_nm\": "
				    "[...], \"reflectance\": [...] } of 1 to "
				    "64 equal lengths");
		for (i = 0; i < n; i++) {
			const cJSON *x = cJSON_GetArrayItem(l, i),
				    *y = cJSON_GetArrayItem(r, i);

			if (!cJSON_IsNumber(x) || !cJSON_IsNumber(y))
				return fail(c, STRAY_EINVAL,
					    "reflectance_table",
					    "entries must be numbers");
			t->nm[i] = x->valuedouble;
			t->rho[i] = y->valuedouble;
		}
	}
	for (i = 0; i < n; i++) {
		if (!(t->nm[i] > 0.0 && isfinite(t->nm[i])) ||
		    (i > 0 && !(t->nm[i] > t->nm[i - 1])))
			return fail(c, STRAY_EINVAL, "reflectance_table",
				    "wavelength_nm must be > 0 and increasing");
		if (!(t->rho[i] >= 0.0 && t->rho[i] <= 1.0))
			return fail(c, STRAY_EINVAL, "reflectance_table",
				    "reflectance must be in [0, 1]");
		sum += t->rho[i];
	}
	t->n = n;
	b->rho = sum / n;
	return STRAY_OK;
}

int tracer_json_material(const struct ctx *c, const cJSON *m,
			 struct tracer_brdf *b, struct tracer_rho_table *tab)
{
	const cJSON *t = cJSON_GetObjectItemCaseSensitive(m, "type");
	const char *type = cJSON_IsString(t) ? t->valuestring : "";
	int rc = STRAY_OK;

	memset(b, 0, sizeof(*b));
	tab->n = 0;
	b->rho = 1.0;
	if (strcmp(type, "absorber") == 0)
		return STRAY_OK;
	if (strcmp(type, "lambert") == 0)
		b->ops = &tracer_brdf_lambert_ops;
	else if (strcmp(type, "mirror") == 0)
		b->ops = &tracer_brdf_mirror_ops;
	else if (strcmp(type, "abg") == 0)
		b->ops = &tracer_brdf_abg_ops;
	else
		return fail(c, STRAY_EINVAL, "type", "must be lambert, mirror, "
			    "abg or absorber");
	rc = tracer_json_number(c, m, "reflectance", &b->rho, b->ops ==
		    &tracer_brdf_lambert_ops &&
		    !cJSON_GetObjectItemCaseSensitive(m, "reflectance_table"));
	if (!rc && b->ops == &tracer_brdf_abg_ops)
		rc = tracer_json_number(c, m, "a", &b->abg.a, 1) ||
		     tracer_json_number(c, m, "b", &b->abg.b, 1) ||
		     tracer_json_number(c, m, "g", &b->abg.g, 1);
	if (!rc && (b->rho < 0.0 || b->rho > 1.0))
		rc = fail(c, STRAY_EINVAL, "reflectance", "must be in [0, 1]");
	if (!rc)
		rc = rho_table(c, m, b, tab);
	if (!rc && b->ops == &tracer_brdf_abg_ops &&
	    !(b->abg.a >= 0.0 && b->abg.b > 0.0 && b->abg.g >= 0.0))
		rc = fail(c, STRAY_EINVAL, "abg", "needs a >= 0, b > 0, g >= 0");
	return rc ? c->err ? c->err->code : STRAY_EINVAL : STRAY_OK;
}

int tracer_json_group_material(const struct ctx *c, const cJSON *m,
			       const char *mname, struct tracer_scene *s,
			       size_t g)
{
	int rc = tracer_json_material(c, m, &s->material[g], &s->spectral[g]);

	if (rc)
		stray_error_text(c->err, mname);
	return rc;
}
