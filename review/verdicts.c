/*
 * verdicts.c - review.json: each requirement of the project against the
 * value a step found (with its interval), pass or fail, the figure that
 * shows it, and the steps as the manifest has them.  Values are read
 * from the steps' own --json outputs only: a requirement whose step did
 * not run has found = null and fails, it is never filled in.
 */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "review/review.h"
#include "review_int.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/provenance.h"

cJSON *review_read_json(const char *dir, const char *name)
{
	char path[REVIEW_PATH_MAX * 2], *text = NULL;
	struct stray_error e;
	size_t len;
	cJSON *j;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	if (access_ok(path) != 0 || stray_file_read(path, &text, &len, &e))
		return NULL;
	j = cJSON_ParseWithLength(text, len);
	free(text);
	return j;
}

const struct review_step *review_step_named(const struct review_plan *plan,
					    const char *name)
{
	int i;

	for (i = 0; i < plan->n; i++)
		if (strcmp(plan->step[i].name, name) == 0)
			return &plan->step[i];
	return NULL;
}

int review_step_done(const struct review_plan *plan, const char *name)
{
	const struct review_step *s = review_step_named(plan, name);

	return s && s->status && strcmp(s->status, "done") == 0;
}

static double num(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);

	return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* The source of each requirement: step, JSON file, how to read it. */
static void find(const char *dir, const struct review_plan *plan,
		 const char *key, struct review_verdict *v)
{
	static const char *const body[3][3] = {
		{ "sun_exclusion_deg_max", "sun_deg", "sun" },
		{ "moon_exclusion_deg_max", "moon_deg", "moon" },
		{ "earth_exclusion_deg_max", "earth_limb_deg", "earth" } };
	cJSON *j;
	int b;

	v->found = v->lo = v->hi = NAN;
	for (b = 0; b < 3; b++)
		if (strcmp(key, body[b][0]) == 0) {
			v->step = "exclusion";
			v->unit = "deg";
			v->figure = "exclusion.png";
			v->le = 1;
			if (!review_step_done(plan, v->step) ||
			    !(j = review_read_json(dir, "exclusion.json")))
				return;
			v->found = num(j, body[b][1]);
			v->lo = num(cJSON_GetObjectItemCaseSensitive(j, body[b][2]), "deg_lo");
			v->hi = num(cJSON_GetObjectItemCaseSensitive(j, body[b][2]), "deg_hi");
			cJSON_Delete(j);
			return;
		}
	if (strcmp(key, "false_stars_per_image") == 0) {
		v->step = "fdr_at_requirement";
		v->unit = "false stars per image";
		v->figure = "fdr.png";
		v->le = 1;
		if (review_step_done(plan, v->step) &&
		    (j = review_read_json(dir, "fdr_at_requirement.json"))) {
			v->found = num(j, "fdr");
			cJSON_Delete(j);
		}
		return;
	}
	v->step = "availability";
	v->unit = "fraction of the mission";
	v->figure = "availability_timeline.png";
	v->le = 0;
	if (review_step_done(plan, v->step) &&
	    (j = review_read_json(dir, "availability.json"))) {
		v->found = num(j, "any_head_available_frac");
		cJSON_Delete(j);
	}
}

int review_verdicts(const char *dir, const struct review_project *p,
		    const struct review_plan *plan, struct review_verdict *v)
{
	int i;

	for (i = 0; i < p->n_req; i++) {
		memset(&v[i], 0, sizeof(v[i]));
		v[i].key = p->req[i].key;
		v[i].required = p->req[i].value;
		find(dir, plan, v[i].key, &v[i]);
		v[i].pass = isfinite(v[i].found) &&
			    (v[i].le ? v[i].found <= v[i].required
				     : v[i].found >= v[i].required);
		if (!review_step_done(plan, v[i].step) ||
		    !exists_file(dir, v[i].figure))
			v[i].figure = NULL;
	}
	return p->n_req;
}

static cJSON *number_or_null(double x)
{
	return isfinite(x) ? cJSON_CreateNumber(x) : cJSON_CreateNull();
}

cJSON *review_step_json(const struct review_step *s, cJSON *outputs)
{
	cJSON *j = cJSON_CreateObject();

	cJSON_AddStringToObject(j, "name", s->name);
	cJSON_AddStringToObject(j, "status", s->status ? s->status : "not run");
	cJSON_AddNumberToObject(j, "seconds", s->seconds);
	cJSON_AddItemToObject(j, "outputs", outputs);
	if (s->why)
		cJSON_AddStringToObject(j, "why", s->why);
	else
		cJSON_AddNullToObject(j, "why");
	return j;
}

static cJSON *steps_json(const char *dir, const struct review_plan *plan)
{
	cJSON *a = cJSON_CreateArray();
	int i, k;

	for (i = 0; i < plan->n; i++) {
		const struct review_step *s = &plan->step[i];
		cJSON *o = cJSON_CreateArray();
		int done = s->status && strcmp(s->status, "done") == 0;

		for (k = 0; done && k < s->n_outs; k++)
			if (exists_file(dir, s->outs[k]))
				cJSON_AddItemToArray(o, cJSON_CreateString(s->outs[k]));
		cJSON_AddItemToArray(a, review_step_json(s, o));
	}
	return a;
}

int review_write_json(const char *dir, const struct review_project *p,
		      const struct review_plan *plan,
		      const struct review_verdict *v, int n,
		      struct stray_error *err)
{
	char path[REVIEW_PATH_MAX * 2], *text;
	struct stray_file_out fo;
	cJSON *root = cJSON_CreateObject(), *a = cJSON_CreateArray();
	int i, rc;

	cJSON_AddStringToObject(root, "name", p->name);
	cJSON_AddStringToObject(root, "version", stray_provenance_version());
	cJSON_AddItemToObject(root, "verdicts", a);
	for (i = 0; i < n; i++) {
		cJSON *j = cJSON_CreateObject(), *iv;

		cJSON_AddStringToObject(j, "requirement", v[i].key);
		cJSON_AddNumberToObject(j, "required", v[i].required);
		cJSON_AddItemToObject(j, "found", number_or_null(v[i].found));
		if (isfinite(v[i].lo) && isfinite(v[i].hi)) {
			iv = cJSON_CreateArray();
			cJSON_AddItemToArray(iv, cJSON_CreateNumber(v[i].lo));
			cJSON_AddItemToArray(iv, cJSON_CreateNumber(v[i].hi));
		} else {
			iv = cJSON_CreateNull();
		}
		cJSON_AddItemToObject(j, "interval", iv);
		cJSON_AddStringToObject(j, "unit", v[i].unit);
		cJSON_AddBoolToObject(j, "pass", v[i].pass);
		if (v[i].figure)
			cJSON_AddStringToObject(j, "figure", v[i].figure);
		else
			cJSON_AddNullToObject(j, "figure");
		cJSON_AddStringToObject(j, "step", v[i].step);
		cJSON_AddItemToArray(a, j);
	}
	cJSON_AddItemToObject(root, "steps", steps_json(dir, plan));
	text = cJSON_Print(root);
	cJSON_Delete(root);
	if (!text)
		return stray_error_set(err, STRAY_ENOMEM, "review.json", NULL);
	snprintf(path, sizeof(path), "%s/review.json", dir);
	if ((rc = stray_file_open_atomic(&fo, path, err)) == STRAY_OK) {
		fputs(text, fo.f);
		fputc('\n', fo.f);
		rc = stray_file_commit(&fo, err);
	}
	free(text);
	return rc;
}
