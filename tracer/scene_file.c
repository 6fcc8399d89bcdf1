/*
 * scene_file.c - JSON scene files (cJSON): meshes, a material per surface
 * group, the detector and the beam.  Mesh paths are relative to the scene
 * file.  Example:
 *
 *   { "meshes": [ { "file": "baffle.obj" },
 *                 { "file": "lens_mount.stl", "group": "mount" } ],
 *     "materials": { "black": { "type": "lambert", "reflectance": 0.04 },
 *                    "shiny": { "type": "mirror", "reflectance": 1 },
 *                    "paint": { "type": "abg", "a": 0.01, "b": 0.01,
 *                               "g": 2 },
 *                    "dead":  { "type": "absorber" } },
 *     "groups": { "exterior": "shiny", "detector": "dead" },
 *     (a material's reflectance may change with wavelength, issue 17:
 *      "reflectance_table": "black.csv" (wavelength_nm,reflectance,
 *      relative to the scene file) or { "wavelength_nm": [...],
 *      "reflectance": [...] }; tracer/spectral.h)
 *     "default_material": "black",
 *     "detector": { "shape": "disk", "center": [0, 0, -40],
 *                   "normal": [0, 0, 1], "radius_mm": 6.5 },
 *     "beam": { "center": [0, 0, 0], "normal": [0, 0, 1],
 *               "radius_mm": 14 } }
 * The beam is every ray through the aperture disk (centre, normal toward
 * the sky, radius); normal defaults to +z; "radius_mm": "auto" (or left
 * out) over-fills the mesh (its widest vertex from the beam axis).
 * A file with "type": "vanes" describes a parametric vane baffle instead
 * (tracer/scene_vanes.c); both read materials through scene_json.c.
 */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/mesh_import.h"
#include "tracer/scene_file.h"
#include "scene_json.h"
#include "tracer/mesh_edges.h"

#define ctx tracer_json_ctx

static int fail(const struct ctx *c, int code, const char *field,
		const char *reason)
{
	return stray_error_at(c->err, code, c->path, 0, field, reason);
}

/* Through the hosted reader: its size limit, a directory refused, and
 * a missing file is bad input (exit 2), not a failure. */
static char *read_text(const struct ctx *c, int *rc)
{
	struct stray_error io;
	char *buf;
	size_t len;

	stray_error_clear(&io);
	*rc = stray_file_read(c->path, &buf, &len, &io);
	if (*rc == STRAY_ENOTFOUND)
		return (*rc = fail(c, STRAY_ENOTFOUND, "--scene",
			"is neither a built-in scene (ref4) nor a file")), NULL;
	if (*rc != STRAY_OK) {
		if (c->err && c->err->code == STRAY_OK)
			*c->err = io;
		return NULL;
	}
	return buf;
}

static int vec(const struct ctx *c, const cJSON *o, const char *key,
	       struct vec3 *v)
{
	const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, key);
	double x[3];
	int i;

	if (!cJSON_IsArray(a) || cJSON_GetArraySize(a) != 3)
		return fail(c, STRAY_EINVAL, key, "must be [x, y, z]");
	for (i = 0; i < 3; i++) {
		const cJSON *e = cJSON_GetArrayItem(a, i);

		if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
			return fail(c, STRAY_EINVAL, key, "must be [x, y, z]");
		x[i] = e->valuedouble;
	}
	*v = v3(x[0], x[1], x[2]);
	return STRAY_OK;
}

static int meshes(const struct ctx *c, const cJSON *root,
		  struct tracer_mesh *m)
{
	const cJSON *arr = cJSON_GetObjectItemCaseSensitive(root, "meshes");
	const cJSON *it;
	char path[PATH_MAX];

	if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) == 0)
		return fail(c, STRAY_EINVAL, "meshes", "must be a non-empty list");
	cJSON_ArrayForEach(it, arr) {
		const cJSON *f = cJSON_GetObjectItemCaseSensitive(it, "file");
		const cJSON *g = cJSON_GetObjectItemCaseSensitive(it, "group");
		double scale = 1.0;
		int rc;

		if (!cJSON_IsString(f) || (g && !cJSON_IsString(g)))
			return fail(c, STRAY_EINVAL, "meshes",
				    "each needs a \"file\" (and a string \"group\")");
		rc = tracer_json_number(c, it, "scale_mm", &scale, 0);
		if (rc)
			return rc;
		tracer_json_sibling(c->path, f->valuestring, path, sizeof(path));
		rc = tracer_mesh_import(m, path, g ? g->valuestring : NULL,
					scale, c->err);
		if (rc)
			return rc;
	}
	return STRAY_OK;
}

/* Each surface group's material: "groups" map, same-named material, or
 * "default_material". */
static int assign(const struct ctx *c, const cJSON *root,
		  struct tracer_scene *s)
{
	const cJSON *mats = cJSON_GetObjectItemCaseSensitive(root, "materials");
	const cJSON *map = cJSON_GetObjectItemCaseSensitive(root, "groups");
	const cJSON *def = cJSON_GetObjectItemCaseSensitive(root,
							   "default_material");
	size_t g;

	if (!cJSON_IsObject(mats))
		return fail(c, STRAY_EINVAL, "materials", "must be an object");
	for (g = 0; g < s->mesh.n_group; g++) {
		const char *gname = s->mesh.group_name[g];
		const cJSON *name = cJSON_GetObjectItemCaseSensitive(map, gname);
		const char *mname = cJSON_IsString(name) ? name->valuestring :
				    cJSON_GetObjectItemCaseSensitive(mats, gname) ?
				    gname : cJSON_IsString(def) ?
				    def->valuestring : NULL;
		const cJSON *m = mname ?
			cJSON_GetObjectItemCaseSensitive(mats, mname) : NULL;
		int rc;

		if (!m)
			return tracer_json_fail_text(c, STRAY_ENOTFOUND,
				"groups", "surface group has no material",
				gname);
		rc = tracer_json_group_material(c, m, mname, s, g);
		if (rc)
			return rc;
	}
	return STRAY_OK;
}

/* A beam that over-fills the whole mesh: its widest vertex from the
 * beam axis (plus 1 %), so no opening of the geometry as built is
 * clipped, whatever its edges (issue 17 item 0). */
static double overfill_radius(const struct tracer_scene *s)
{
	struct vec3 n = v3_norm(s->beam.normal);
	double r2 = 0.0;
	size_t i;

	for (i = 0; i < s->mesh.n_vert; i++) {
		struct vec3 q = v3_sub(v3(s->mesh.vert[3 * i],
					  s->mesh.vert[3 * i + 1],
					  s->mesh.vert[3 * i + 2]),
				       s->beam.center);
		struct vec3 t = v3_sub(q, v3_scale(n, v3_dot(q, n)));

		r2 = fmax(r2, v3_dot(t, t));
	}
	return 1.01 * sqrt(r2);
}

static int detector_and_beam(const struct ctx *c, const cJSON *root,
			     struct tracer_scene *s)
{
	const cJSON *d = cJSON_GetObjectItemCaseSensitive(root, "detector");
	const cJSON *b = cJSON_GetObjectItemCaseSensitive(root, "beam");
	const cJSON *shape = cJSON_GetObjectItemCaseSensitive(d, "shape");
	struct tracer_detector *det = &s->det;
	int rc;

	if (!cJSON_IsObject(d) || !cJSON_IsObject(b))
		return fail(c, STRAY_EINVAL, !cJSON_IsObject(d) ? "detector" :
			    "beam", "is missing");
	rc = vec(c, d, "center", &det->center);
	if (!rc)
		rc = vec(c, d, "normal", &det->normal);
	det->normal = v3_norm(det->normal);
	if (!rc)
		rc = tracer_json_number(c, d, "accept_half_angle_deg",
			    &det->accept_half_angle_deg, 0);
	if (!rc && cJSON_IsString(shape) &&
	    strcmp(shape->valuestring, "rect") == 0) {
		det->shape = TRACER_DET_RECT;
		rc = tracer_json_number(c, d, "width_mm", &det->half_w_mm, 1);
		if (!rc)
			rc = tracer_json_number(c, d, "height_mm", &det->half_h_mm, 1);
		det->half_w_mm *= 0.5;
		det->half_h_mm *= 0.5;
	} else if (!rc) {
		det->shape = TRACER_DET_DISK;
		rc = tracer_json_number(c, d, "radius_mm", &det->radius_mm, 1);
	}
	if (!rc)
		rc = vec(c, b, "center", &s->beam.center);
	s->beam.normal = v3(0.0, 0.0, 1.0);
	if (!rc && cJSON_GetObjectItemCaseSensitive(b, "normal"))
		rc = vec(c, b, "normal", &s->beam.normal);
	s->beam.normal = v3_norm(s->beam.normal);
	if (!rc && (!cJSON_GetObjectItemCaseSensitive(b, "radius_mm") ||
	    (cJSON_IsString(cJSON_GetObjectItemCaseSensitive(b, "radius_mm")) &&
	     strcmp(cJSON_GetObjectItemCaseSensitive(b,
		    "radius_mm")->valuestring, "auto") == 0)))
		s->beam.radius_mm = overfill_radius(s);
	else if (!rc)
		rc = tracer_json_number(c, b, "radius_mm", &s->beam.radius_mm, 1);
	if (!rc && !(s->beam.radius_mm > 0.0))
		rc = fail(c, STRAY_EINVAL, "radius_mm", "beam must be wider than 0");
	if (!rc && tracer_detector_check(det, c->err))
		rc = fail(c, c->err ? c->err->code : STRAY_EINVAL, "detector",
			  "is invalid");
	return rc;
}

/* 1-based line of a byte offset in text. */
static long line_of(const char *text, const char *at)
{
	long line = 1;

	for (; text < at && *text; text++)
		line += *text == '\n';
	return line;
}

int tracer_scene_file_load(const char *path, struct tracer_scene *s,
			   struct stray_error *err)
{
	return tracer_scene_file_load_sets(path, NULL, 0, s, err);
}

/* The keys a mesh scene takes as `--set key=value`: what needs no
 * parametric geometry (issue 17 item 2). */
static int mesh_sets(const char *path, const char *const *sets, int n,
		     struct tracer_scene *s, struct stray_error *err)
{
	int i;

	for (i = 0; i < n; i++) {
		const char *eq = strchr(sets[i], '=');
		char *end;
		double v = eq ? strtod(eq + 1, &end) : NAN;
		size_t len = eq ? (size_t)(eq - sets[i]) : 0;

		if (!eq || end == eq + 1 || *end || !isfinite(v)) {
			stray_error_at(err, STRAY_EINVAL, path, 0, "--set",
				       "expected key=number");
			stray_error_text(err, sets[i]);
			return STRAY_EINVAL;
		}
		if (len == 21 && strncmp(sets[i], "accept_half_angle_deg",
					 len) == 0 && v >= 0.0 && v <= 90.0) {
			s->det.accept_half_angle_deg = v;
		} else if (len == 11 && strncmp(sets[i], "edge_radius",
						len) == 0 && v >= 0.0) {
			int rc = tracer_mesh_round_edges(s, v, err);

			if (rc)
				return rc;
		} else {
			stray_error_at(err, STRAY_EINVAL, path, 0, "--set",
				       "a mesh scene takes only "
				       "accept_half_angle_deg (0-90) and "
				       "edge_radius (>= 0)");
			stray_error_text(err, sets[i]);
			return STRAY_EINVAL;
		}
	}
	return STRAY_OK;
}

int tracer_scene_file_load_sets(const char *path, const char *const *sets,
				int n_sets, struct tracer_scene *s,
				struct stray_error *err)
{
	struct ctx c = { path, err };
	const cJSON *type;
	cJSON *root;
	char *text;
	int rc;

	text = read_text(&c, &rc);
	if (!text)
		return rc;
	root = cJSON_Parse(text);
	if (!root) {
		const char *at = cJSON_GetErrorPtr();

		rc = stray_error_at(err, STRAY_EPARSE, path,
				    at ? line_of(text, at) : 0, "--scene",
				    "malformed JSON");
		free(text);
		return rc;
	}
	type = cJSON_GetObjectItemCaseSensitive(root, "type");
	if (type && !(cJSON_IsString(type) &&
		      (strcmp(type->valuestring, "vanes") == 0 ||
		       strcmp(type->valuestring, "mesh") == 0))) {
		rc = fail(&c, STRAY_EINVAL, "type", "must be mesh or vanes");
	} else if (type && strcmp(type->valuestring, "vanes") == 0) {
		rc = tracer_scene_vanes_build(&c, root, sets, n_sets, s);
	} else {
		rc = meshes(&c, root, &s->mesh);
		if (!rc)
			rc = assign(&c, root, s);
		if (!rc)
			rc = detector_and_beam(&c, root, s);
		if (!rc)	/* before edge rounding: it needs outward */
			rc = tracer_scene_mesh_checks(path, s, err);
		if (!rc)
			rc = mesh_sets(path, sets, n_sets, s, err);
	}
	cJSON_Delete(root);
	free(text);
	return rc;
}

int tracer_scene_file_is_vanes(const char *path)
{
	char *text;
	size_t len;
	cJSON *root;
	const cJSON *t;
	int yes;

	if (stray_file_read(path, &text, &len, NULL) != STRAY_OK)
		return 0;
	root = cJSON_Parse(text);
	free(text);
	t = cJSON_GetObjectItemCaseSensitive(root, "type");
	yes = cJSON_IsString(t) && strcmp(t->valuestring, "vanes") == 0;
	cJSON_Delete(root);
	return yes;
}
