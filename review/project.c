/*
 * project.c - the project file of `stray review` (docs/review.md): one
 * JSON object naming the sensor, the scene with its overrides, the lens,
 * the requirements and, optionally, a measured curve, a mission and
 * heads.  Unknown keys are an error (a typo must not drop a requirement);
 * paths are taken relative to the file, so a project folder can move.
 */
#include <cjson/cJSON.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "review/review.h"
#include "review_int.h"
#include "stray/detector.h"
#include "stray/errfmt.h"
#include "stray/file.h"

static const char *const req_keys[REVIEW_REQ_MAX] = {
	"false_stars_per_image", "sun_exclusion_deg_max",
	"moon_exclusion_deg_max", "earth_exclusion_deg_max",
	"availability_min"
};

/* A file relative to the project's folder, or a built-in name (a bare
 * word that is no file there) passed on as it is. */
static int take_path(const struct review_project *p, const cJSON *v,
		     const char *key, int builtin_ok, char *dst,
		     struct stray_error *err)
{
	char joined[REVIEW_PATH_MAX * 2];
	const char *s;

	if (!cJSON_IsString(v) || !v->valuestring[0])
		return review_bad(err, p, key, NULL, "must be a non-empty string");
	s = v->valuestring;
	if (s[0] == '/')
		snprintf(joined, sizeof(joined), "%s", s);
	else
		snprintf(joined, sizeof(joined), "%s/%s", p->dir, s);
	if (access(joined, F_OK) == 0) {
		if (!realpath(joined, dst))
			return review_bad(err, p, key, s, "path cannot be resolved");
		return STRAY_OK;
	}
	if (builtin_ok && !strchr(s, '/') && !strchr(s, '.') &&
	    strlen(s) < 64) {
		snprintf(dst, REVIEW_PATH_MAX, "%s", s);
		return STRAY_OK;
	}
	return review_bad(err, p, key, s, "no such file (paths are relative to the project file)");
}

static int take_number(const struct review_project *p, const cJSON *v,
		       const char *key, double lo, double hi, double *out,
		       struct stray_error *err)
{
	char text[64];

	if (!cJSON_IsNumber(v))
		return review_bad(err, p, key, NULL, "must be a number");
	if (!(v->valuedouble >= lo && v->valuedouble <= hi)) {
		snprintf(text, sizeof(text), "%g", v->valuedouble);
		snprintf(text + strlen(text), sizeof(text) - strlen(text),
			 " (allowed %g..%g)", lo, hi);
		return review_bad(err, p, key, text, "out of range");
	}
	*out = v->valuedouble;
	return STRAY_OK;
}

static int take_set(struct review_project *p, const cJSON *set,
		    struct stray_error *err)
{
	const cJSON *it;
	const char *dup;
	int n;

	if (!cJSON_IsObject(set))
		return review_bad(err, p, "set", NULL, "must be an object of scene keys");
	if (review_dup_key(set, &dup))
		return review_bad(err, p, "set", dup, "key given twice");
	cJSON_ArrayForEach(it, set) {
		if (p->n_set >= REVIEW_SET_MAX)
			return review_bad(err, p, "set", it->string, "more than 24 overrides");
		if (cJSON_IsNumber(it))
			n = snprintf(p->set[p->n_set], sizeof(p->set[0]),
				     "%s=%.10g", it->string, it->valuedouble);
		else if (cJSON_IsString(it))
			n = snprintf(p->set[p->n_set], sizeof(p->set[0]),
				     "%s=%s", it->string, it->valuestring);
		else
			return review_bad(err, p, "set", it->string,
				   "value must be a number or a string");
		if (n < 0 || (size_t)n >= sizeof(p->set[0]) ||
		    strchr(it->string, '='))
			return review_bad(err, p, "set", it->string, "bad override");
		p->n_set++;
	}
	return STRAY_OK;
}

static int take_lens(struct review_project *p, const cJSON *v,
		     struct stray_error *err)
{
	static const char *const ideal_keys[] = { "fov_half_deg", NULL };
	const cJSON *x;

	if (cJSON_IsString(v) && strcmp(v->valuestring, "ideal") == 0) {
		p->lens = REVIEW_LENS_IDEAL;	/* the sensor's field */
		return STRAY_OK;
	}
	if (cJSON_IsString(v)) {
		p->lens = REVIEW_LENS_CSV;
		return take_path(p, v, "lens", 0, p->lens_path, err);
	}
	if (cJSON_IsObject(v) && cJSON_GetArraySize(v) == 1 &&
	    (x = cJSON_GetObjectItemCaseSensitive(v, "sweep"))) {
		p->lens = REVIEW_LENS_SWEEP;
		return take_path(p, x, "lens.sweep", 0, p->lens_path, err);
	}
	if (cJSON_IsObject(v) && cJSON_GetArraySize(v) == 1 &&
	    (x = cJSON_GetObjectItemCaseSensitive(v, "ideal"))) {
		p->lens = REVIEW_LENS_IDEAL;
		if (!cJSON_IsObject(x) ||
		    review_only_keys(x, ideal_keys, "lens.ideal", p, err) != STRAY_OK)
			return review_bad(err, p, "lens.ideal", NULL,
				   "must be {\"fov_half_deg\": DEG}");
		x = cJSON_GetObjectItemCaseSensitive(x, "fov_half_deg");
		return x ? take_number(p, x, "lens.ideal.fov_half_deg", 0.1,
				       60, &p->lens_fov_deg, err) : STRAY_OK;
	}
	return review_bad(err, p, "lens", NULL,
		   "must be \"ideal\", {\"ideal\": {...}}, a CSV or {\"sweep\": DIR}");
}

static int take_requirements(struct review_project *p, const cJSON *r,
			     struct stray_error *err)
{
	static const double hi[REVIEW_REQ_MAX] = { 1e6, 180, 180, 180, 1 };
	const cJSON *it;
	const char *dup;
	int i, rc;

	if (!cJSON_IsObject(r) || !r->child)
		return review_bad(err, p, "requirements", NULL,
			   "must be an object with at least one requirement");
	/* each known at most once: at most REVIEW_REQ_MAX of them */
	if (review_dup_key(r, &dup))
		return review_bad(err, p, "requirements", dup, "given twice");
	cJSON_ArrayForEach(it, r) {
		for (i = 0; i < REVIEW_REQ_MAX; i++)
			if (strcmp(it->string, req_keys[i]) == 0)
				break;
		if (i == REVIEW_REQ_MAX)
			return review_bad(err, p, "requirements", it->string,
				   "unknown requirement (docs/review.md)");
		p->req[p->n_req].key = req_keys[i];
		rc = take_number(p, it, req_keys[i], i == 0 ? 1e-6 : 0,
				 hi[i], &p->req[p->n_req].value, err);
		if (rc != STRAY_OK)
			return rc;
		p->n_req++;
	}
	return STRAY_OK;
}

static int take_measured(struct review_project *p, const cJSON *m,
			 struct stray_error *err)
{
	static const char *const keys[] = { "curve", "kind", NULL };
	const cJSON *k;
	int rc;

	if (!cJSON_IsObject(m))
		return review_bad(err, p, "measured", NULL, "must be {\"curve\": F, \"kind\": \"baffle\"|\"system\"}");
	if ((rc = review_only_keys(m, keys, "measured", p, err)) != STRAY_OK)
		return rc;
	rc = take_path(p, cJSON_GetObjectItemCaseSensitive(m, "curve"),
		       "measured.curve", 0, p->measured, err);
	k = cJSON_GetObjectItemCaseSensitive(m, "kind");
	if (rc == STRAY_OK && k) {
		if (!cJSON_IsString(k) || (strcmp(k->valuestring, "baffle") &&
					   strcmp(k->valuestring, "system")))
			return review_bad(err, p, "measured.kind",
				   cJSON_IsString(k) ? k->valuestring : NULL,
				   "must be \"baffle\" or \"system\"");
		p->measured_system = strcmp(k->valuestring, "system") == 0;
	}
	return rc;
}

/* "detector": thesis, window, threshold or tetra3 (stray/detector.h);
 * "detector_sigma": tetra3's k, 0.5..20. */
static int take_detector(struct review_project *p, const cJSON *root,
			 struct stray_error *err)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, "detector");
	enum stray_detector_kind k;

	if (v && (!cJSON_IsString(v) ||
		  stray_detector_parse(v->valuestring, &k, NULL) != STRAY_OK))
		return review_bad(err, p, "detector", cJSON_IsString(v) ?
			v->valuestring : NULL,
			"must be thesis, window, threshold or tetra3");
	if (v)
		snprintf(p->detector, sizeof(p->detector), "%s", v->valuestring);
	v = cJSON_GetObjectItemCaseSensitive(root, "detector_sigma");
	return v ? take_number(p, v, "detector_sigma", 0.5, 20,
			       &p->detector_sigma, err) : STRAY_OK;
}

/* defined in mission.c: the mission and heads keys */
int review_take_mission(struct review_project *p, const cJSON *m,
			struct stray_error *err);
int review_take_heads(struct review_project *p, const cJSON *h,
		      struct stray_error *err);

static int take_all(struct review_project *p, const cJSON *root,
		    struct stray_error *err)
{
	static const char *const keys[] = { "name", "sensor", "scene", "set",
		"lens", "requirements", "measured", "mission", "heads",
		"detector", "detector_sigma", NULL };
	static const char *const need[] = { "sensor", "scene", "requirements" };
	const cJSON *v;
	int i, rc;

	if ((rc = review_only_keys(root, keys, "project", p, err)) != STRAY_OK)
		return rc;
	for (i = 0; i < 3; i++)
		if (!cJSON_GetObjectItemCaseSensitive(root, need[i]))
			return review_bad(err, p, need[i], NULL, "is required");
	v = cJSON_GetObjectItemCaseSensitive(root, "name");
	if (v && (!cJSON_IsString(v) || !v->valuestring[0] ||
		  strlen(v->valuestring) >= sizeof(p->name)))
		return review_bad(err, p, "name", NULL, "must be a string of 1..127 characters");
	if (v)
		snprintf(p->name, sizeof(p->name), "%s", v->valuestring);
	rc = take_path(p, cJSON_GetObjectItemCaseSensitive(root, "sensor"),
		       "sensor", 1, p->sensor, err);
	if (rc == STRAY_OK)
		rc = take_path(p, cJSON_GetObjectItemCaseSensitive(root, "scene"),
			       "scene", 1, p->scene, err);
	if (rc == STRAY_OK && (v = cJSON_GetObjectItemCaseSensitive(root, "set")))
		rc = take_set(p, v, err);
	if (rc == STRAY_OK)
		rc = take_detector(p, root, err);
	if (rc == STRAY_OK && (v = cJSON_GetObjectItemCaseSensitive(root, "lens")))
		rc = take_lens(p, v, err);
	if (rc == STRAY_OK)
		rc = take_requirements(p, cJSON_GetObjectItemCaseSensitive(root, "requirements"), err);
	if (rc == STRAY_OK && (v = cJSON_GetObjectItemCaseSensitive(root, "measured")))
		rc = take_measured(p, v, err);
	if (rc == STRAY_OK && (v = cJSON_GetObjectItemCaseSensitive(root, "mission")))
		rc = review_take_mission(p, v, err);
	if (rc == STRAY_OK && (v = cJSON_GetObjectItemCaseSensitive(root, "heads")))
		rc = review_take_heads(p, v, err);
	if (rc == STRAY_OK && p->n_heads && p->mission == REVIEW_MISSION_NONE)
		return review_bad(err, p, "heads", NULL, "need a mission to fly along");
	return rc;
}

int review_project_parse(const char *path, const char *dir, const char *text,
			 size_t len, struct review_project *p,
			 struct stray_error *err)
{
	cJSON *root;
	int rc;

	memset(p, 0, sizeof(*p));
	p->incl_deg = -1.0;
	snprintf(p->path, sizeof(p->path), "%s", path);
	snprintf(p->dir, sizeof(p->dir), "%s", dir);
	root = cJSON_ParseWithLength(text, len);
	if (!root || !cJSON_IsObject(root)) {
		cJSON_Delete(root);
		return stray_error_at(err, STRAY_EPARSE, p->path, 0, "json",
				      "not a JSON object");
	}
	rc = take_all(p, root, err);
	cJSON_Delete(root);
	if (rc == STRAY_OK && !p->name[0]) {
		/* no name: the file's own name, never a built-in example's */
		const char *base = strrchr(p->path, '/');

		snprintf(p->name, sizeof(p->name), "%.127s", base ? base + 1 : p->path);
	}
	return rc;
}

int review_project_load(const char *path, struct review_project *p,
			struct stray_error *err)
{
	char full[REVIEW_PATH_MAX], dir[REVIEW_PATH_MAX], *text = NULL, *slash;
	size_t len;
	int rc;

	memset(p, 0, sizeof(*p));
	if (!realpath(path, full))
		return stray_error_at(err, STRAY_ENOTFOUND, path, 0, NULL,
				      "no such project file");
	snprintf(dir, sizeof(dir), "%s", full);
	slash = strrchr(dir, '/');
	*(slash == dir ? slash + 1 : slash) = '\0';
	if ((rc = stray_file_read(full, &text, &len, err)) != STRAY_OK)
		return rc;
	rc = review_project_parse(full, dir, text, len, p, err);
	free(text);
	return rc;
}

const char *const *review_req_keys(void)
{
	return req_keys;
}
