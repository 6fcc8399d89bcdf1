/*
 * scene_vanes.c - the vane-baffle family as a scene file (issue 17 item
 * 1): any vane count, positions, apertures, thickness, bevel angle and
 * face, edge radius, tube, pupil and floor, with a material per surface
 * group.  `ref4` is one member (examples/ref4-vanes.json traces
 * byte-identically to `--scene ref4`).  Example:
 *
 *   { "type": "vanes",
 *     "vanes": [ { "z": 0 }, { "z": -13, "aperture_mm": 8.9 },
 *                { "z": -26 } ],
 *     "vane_thickness": 1, "bevel_angle_deg": 45, "bevel_face": "lower",
 *     "edge_radius": 0.05, "cone_half_angle_deg": 10.5,
 *     "tube": { "inner_radius": 20, "wall": 1.5 },
 *     "pupil": { "radius": 6.5, "z": -40 },
 *     "reflectance": 0.04,
 *     "materials": { "shiny": { "type": "lambert", "reflectance": 0.2 } },
 *     "groups": { "vane*_edge": "shiny", "floor": "shiny" } }
 *
 * A vane without "aperture_mm" sits on the cone from the pupil rim.  Any
 * other key of `stray trace --help`'s baffle list may appear at the top
 * (segments, arc_segments, beam_margin, accept_half_angle_deg, ...).
 * Groups (vaneK_top|edge|bevel|bottom, wallK, floor, exterior, detector)
 * keep the parametric material unless "groups" (keys may be shell
 * patterns), a same-named material or "default_material" gives one; the
 * detector always absorbs.
 */
#include <fnmatch.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "tracer/baffle.h"
#include "scene_json.h"

/* An error at a key of the file (a run-time name: copied). */
static int key_fail(const struct tracer_json_ctx *c, const char *key,
		    const char *reason)
{
	int rc = tracer_json_fail(c, STRAY_EINVAL, "key", reason);

	stray_error_column(c->err, key);
	return rc;
}

static int set_number(const struct tracer_json_ctx *c, struct tracer_baffle *b,
		      const char *key, const cJSON *v)
{
	char buf[96];

	if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
		return key_fail(c, key, "must be a number");
	snprintf(buf, sizeof(buf), "%s=%.17g", key, v->valuedouble);
	if (tracer_baffle_set(b, buf, NULL))
		return key_fail(c, key,
			"is not a vanes parameter (or not an integer)");
	return STRAY_OK;
}

/* {"inner_radius": .., "wall": ..} -> prefix_inner_radius, ... */
static int sub_object(const struct tracer_json_ctx *c, struct tracer_baffle *b,
		      const cJSON *o, const char *name,
		      const char *const map[][2], int n_map)
{
	const cJSON *it;
	int i;

	if (!cJSON_IsObject(o))
		return tracer_json_fail(c, STRAY_EINVAL, name,
					"must be an object");
	cJSON_ArrayForEach(it, o) {
		for (i = 0; i < n_map; i++)
			if (strcmp(it->string, map[i][0]) == 0)
				break;
		if (i == n_map)
			return key_fail(c, it->string,
					"is not a key of this object");
		if (set_number(c, b, map[i][1], it))
			return c->err ? c->err->code : STRAY_EINVAL;
	}
	return STRAY_OK;
}

static int vanes_list(const struct tracer_json_ctx *c, struct tracer_baffle *b,
		      const cJSON *a)
{
	const cJSON *v;
	int n = cJSON_GetArraySize(a), k = 0;

	if (!cJSON_IsArray(a) || n < 1 || n > TRACER_VANES_MAX)
		return tracer_json_fail(c, STRAY_EINVAL, "vanes",
					"must be a list of 1 to 8 vanes");
	b->n_vanes = n;
	memset(b->vane_r, 0, sizeof(b->vane_r));
	cJSON_ArrayForEach(v, a) {
		const cJSON *z = cJSON_GetObjectItemCaseSensitive(v, "z");
		const cJSON *r = cJSON_GetObjectItemCaseSensitive(v,
								  "aperture_mm");
		const cJSON *it;

		cJSON_ArrayForEach(it, v)
			if (strcmp(it->string, "z") != 0 &&
			    strcmp(it->string, "aperture_mm") != 0)
				return key_fail(c, it->string,
					"a vane has only z and aperture_mm");
		if (!cJSON_IsNumber(z) || !isfinite(z->valuedouble))
			return tracer_json_fail(c, STRAY_EINVAL, "z",
				"every vane needs a number z (its top face)");
		if (r && !(cJSON_IsNumber(r) && r->valuedouble > 0.0))
			return tracer_json_fail(c, STRAY_EINVAL, "aperture_mm",
						"must be a positive number");
		b->vane_z[k] = z->valuedouble;
		b->vane_r[k] = r ? r->valuedouble : 0.0;
		k++;
	}
	return STRAY_OK;
}

static const char *const tube_keys[][2] = {
	{ "inner_radius", "tube_inner_radius" }, { "wall", "tube_wall" }
};
static const char *const pupil_keys[][2] = {
	{ "radius", "pupil_radius" }, { "z", "pupil_z" }
};
static const char *const skip_keys[] = {
	"type", "materials", "groups", "default_material"
};

static int parameters(const struct tracer_json_ctx *c, const cJSON *root,
		      struct tracer_baffle *b)
{
	const cJSON *it;
	size_t i;
	int rc = STRAY_OK;

	tracer_baffle_ref4(b);
	cJSON_ArrayForEach(it, root) {
		for (i = 0; i < sizeof(skip_keys) / sizeof(skip_keys[0]); i++)
			if (strcmp(it->string, skip_keys[i]) == 0)
				break;
		if (i < sizeof(skip_keys) / sizeof(skip_keys[0]))
			continue;
		if (strcmp(it->string, "vanes") == 0)
			rc = vanes_list(c, b, it);
		else if (strcmp(it->string, "tube") == 0)
			rc = sub_object(c, b, it, "tube", tube_keys, 2);
		else if (strcmp(it->string, "pupil") == 0)
			rc = sub_object(c, b, it, "pupil", pupil_keys, 2);
		else if (strcmp(it->string, "bevel_face") == 0) {
			char buf[64];

			snprintf(buf, sizeof(buf), "bevel_face=%s",
				 cJSON_IsString(it) ? it->valuestring : "?");
			if (tracer_baffle_set(b, buf, NULL))
				rc = tracer_json_fail(c, STRAY_EINVAL,
					"bevel_face", "must be lower or upper");
		} else if (strcmp(it->string, "n_vanes") == 0 ||
			   strncmp(it->string, "vane", 4) == 0) {
			if (strcmp(it->string, "vane_thickness") == 0)
				rc = set_number(c, b, it->string, it);
			else
				rc = key_fail(c, it->string, "give the "
					"vanes as the \"vanes\" list");
		} else
			rc = set_number(c, b, it->string, it);
		if (rc)
			return rc;
	}
	return STRAY_OK;
}

/* The material of group gname from the file, or NULL: keep the baffle's. */
static const char *group_material(const cJSON *root, const char *gname)
{
	const cJSON *mats = cJSON_GetObjectItemCaseSensitive(root, "materials");
	const cJSON *map = cJSON_GetObjectItemCaseSensitive(root, "groups");
	const cJSON *def = cJSON_GetObjectItemCaseSensitive(root,
							   "default_material");
	const cJSON *it, *exact = cJSON_GetObjectItemCaseSensitive(map, gname);

	if (cJSON_IsString(exact))
		return exact->valuestring;
	cJSON_ArrayForEach(it, map)
		if (cJSON_IsString(it) && fnmatch(it->string, gname, 0) == 0)
			return it->valuestring;
	if (cJSON_GetObjectItemCaseSensitive(mats, gname))
		return gname;
	return cJSON_IsString(def) ? def->valuestring : NULL;
}

static int materials(const struct tracer_json_ctx *c, const cJSON *root,
		     struct tracer_scene *s)
{
	const cJSON *mats = cJSON_GetObjectItemCaseSensitive(root, "materials");
	const cJSON *map = cJSON_GetObjectItemCaseSensitive(root, "groups");
	const cJSON *it;
	size_t g;

	if (mats && !cJSON_IsObject(mats))
		return tracer_json_fail(c, STRAY_EINVAL, "materials",
					"must be an object");
	if (map && !cJSON_IsObject(map))
		return tracer_json_fail(c, STRAY_EINVAL, "groups",
					"must be an object");
	cJSON_ArrayForEach(it, map)
		if (!cJSON_IsString(it))
			return key_fail(c, it->string,
					"must name a material");
	for (g = 0; g < s->mesh.n_group; g++) {
		const char *gname = s->mesh.group_name[g];
		const char *mname;
		const cJSON *m;
		int rc;

		if (strcmp(gname, "detector") == 0)
			continue;
		mname = group_material(root, gname);
		if (!mname)
			continue;
		m = cJSON_GetObjectItemCaseSensitive(mats, mname);
		if (!m)
			return tracer_json_fail_text(c, STRAY_ENOTFOUND,
				"groups",
				"names a material not in \"materials\"", mname);
		rc = tracer_json_group_material(c, m, mname, s, g);
		if (rc)
			return rc;
	}
	return STRAY_OK;
}

int tracer_scene_vanes_build(const struct tracer_json_ctx *c,
			     const cJSON *root, const char *const *sets,
			     int n_sets, struct tracer_scene *s)
{
	struct tracer_baffle b;
	int i, rc = parameters(c, root, &b);

	for (i = 0; i < n_sets && !rc; i++)
		rc = tracer_baffle_set(&b, sets[i], c->err);
	if (!rc)	/* the range checks name the field and its value */
		rc = tracer_baffle_build(&b, s, c->err);
	if (rc)
		stray_error_locate(c->err, c->path, 0);
	return rc ? rc : materials(c, root, s);
}
