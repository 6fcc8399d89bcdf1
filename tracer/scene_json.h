/*
 * scene_json.h - what the scene-file readers share (private to tracer/):
 * the file being read for error messages, a material object, the
 * "vanes" family.
 */
#ifndef TRACER_SCENE_JSON_H
#define TRACER_SCENE_JSON_H

#include <cJSON.h>

#include "stray/error.h"
#include "tracer/scene.h"

struct tracer_json_ctx {
	const char *path;
	struct stray_error *err;
};

/* A one-line error naming the file and the field; returns code. */
int tracer_json_fail(const struct tracer_json_ctx *c, int code,
		     const char *field, const char *reason);

/* The same with text (the value at fault) added to the error. */
int tracer_json_fail_text(const struct tracer_json_ctx *c, int code,
			  const char *field, const char *reason,
			  const char *text);

/* o's number key into v: an error naming key when it is not a finite
 * number, or missing and required. */
int tracer_json_number(const struct tracer_json_ctx *c, const cJSON *o,
		       const char *key, double *v, int required);

/* Path of file relative to the scene file's directory. */
void tracer_json_sibling(const char *scene, const char *file, char *out,
			 size_t size);

/* One material object ({"type": "lambert", "reflectance": ...}), with
 * its "reflectance_table" (if any) into tab. */
int tracer_json_material(const struct tracer_json_ctx *c, const cJSON *m,
			 struct tracer_brdf *b, struct tracer_rho_table *tab);

/* Material object m, named mname, into surface group g of s (its BRDF
 * and reflectance table); an error names mname. */
int tracer_json_group_material(const struct tracer_json_ctx *c,
			       const cJSON *m, const char *mname,
			       struct tracer_scene *s, size_t g);

/* A "type": "vanes" file: the parametric baffle with these parameters,
 * then `key=value` sets, built into s, then the per-group materials. */
int tracer_scene_vanes_build(const struct tracer_json_ctx *c,
			     const cJSON *root, const char *const *sets,
			     int n_sets, struct tracer_scene *s);

#endif /* TRACER_SCENE_JSON_H */
