/*
 * mission.c - the "mission" and "heads" keys of a project file: CCSDS
 * OEM/AEM files, or an orbit and an attitude that `stray availability
 * --write-oem/--write-aem` generates (any altitude, inclination or
 * sun-synchronous with an LTAN, epoch, span and step; nadir with yaw
 * steering, inertial or Sun-pointing), and the heads flown along it.
 */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "review/review.h"
#include "review_int.h"
#include "stray/errfmt.h"

static int number(const struct review_project *p, const cJSON *o,
		  const char *key, double lo, double hi, double *out,
		  struct stray_error *err)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
	char text[48];

	if (!v)
		return STRAY_OK;	/* keeps the default */
	if (!cJSON_IsNumber(v))
		return review_bad(err, p, key, NULL, "must be a number");
	if (!(v->valuedouble >= lo && v->valuedouble <= hi)) {
		snprintf(text, sizeof(text), "%g", v->valuedouble);
		return review_bad(err, p, key, text, "out of range (docs/review.md)");
	}
	*out = v->valuedouble;
	return STRAY_OK;
}

static int string(const struct review_project *p, const cJSON *o,
		  const char *key, char *dst, size_t size,
		  struct stray_error *err)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);

	if (!v)
		return STRAY_OK;
	if (!cJSON_IsString(v) || strlen(v->valuestring) >= size)
		return review_bad(err, p, key, NULL, "must be a short string");
	snprintf(dst, size, "%s", v->valuestring);
	return STRAY_OK;
}

static int take_orbit(struct review_project *p, const cJSON *o,
		      struct stray_error *err)
{
	static const char *const keys[] = { "altitude_km", "inclination_deg",
		"ltan", "epoch", "hours", "step_s", NULL };
	int hh, mm, n = 0, rc;

	if (!cJSON_IsObject(o))
		return review_bad(err, p, "mission.orbit", NULL, "must be an object");
	if ((rc = review_only_keys(o, keys, "mission.orbit", p, err)) != STRAY_OK)
		return rc;
	if (!cJSON_GetObjectItemCaseSensitive(o, "altitude_km"))
		return review_bad(err, p, "mission.orbit.altitude_km", NULL, "is required");
	if (!!cJSON_GetObjectItemCaseSensitive(o, "ltan") ==
	    !!cJSON_GetObjectItemCaseSensitive(o, "inclination_deg"))
		return review_bad(err, p, "mission.orbit", NULL,
			   "give one of ltan (sun-synchronous) and inclination_deg");
	p->altitude_km = 550;
	p->hours = 24;
	p->step_s = 60;
	snprintf(p->epoch, sizeof(p->epoch), "2026-06-21");
	rc = number(p, o, "altitude_km", 160, 5000, &p->altitude_km, err);
	if (rc == STRAY_OK)
		rc = number(p, o, "inclination_deg", 0, 180, &p->incl_deg, err);
	if (rc == STRAY_OK)
		rc = number(p, o, "hours", 0.1, 24.0 * 31, &p->hours, err);
	if (rc == STRAY_OK)
		rc = number(p, o, "step_s", 1, 3600, &p->step_s, err);
	if (rc == STRAY_OK)
		rc = string(p, o, "epoch", p->epoch, sizeof(p->epoch), err);
	if (rc == STRAY_OK)
		rc = string(p, o, "ltan", p->ltan, sizeof(p->ltan), err);
	if (rc == STRAY_OK && p->ltan[0] &&
	    (sscanf(p->ltan, "%2d:%2d%n", &hh, &mm, &n) != 2 ||
	     p->ltan[n] || hh > 23 || mm > 59 || hh < 0 || mm < 0))
		return review_bad(err, p, "mission.orbit.ltan", p->ltan, "must be HH:MM");
	return rc;
}

/* A path relative to the project's folder (an absolute one kept). */
static int join(const struct review_project *p, const char *name, char *dst)
{
	int n = name[0] == '/' ? snprintf(dst, REVIEW_PATH_MAX, "%s", name)
			       : snprintf(dst, REVIEW_PATH_MAX, "%.*s/%s",
					  REVIEW_PATH_MAX / 2, p->dir, name);

	return n > 0 && n < REVIEW_PATH_MAX;
}

int review_take_mission(struct review_project *p, const cJSON *m,
			struct stray_error *err);
int review_take_mission(struct review_project *p, const cJSON *m,
			struct stray_error *err)
{
	static const char *const keys[] = { "oem", "aem", "orbit", "attitude",
					    NULL };
	const cJSON *oem, *aem, *orbit;
	int rc;

	if (!cJSON_IsObject(m))
		return review_bad(err, p, "mission", NULL, "must be an object");
	if ((rc = review_only_keys(m, keys, "mission", p, err)) != STRAY_OK)
		return rc;
	oem = cJSON_GetObjectItemCaseSensitive(m, "oem");
	aem = cJSON_GetObjectItemCaseSensitive(m, "aem");
	orbit = cJSON_GetObjectItemCaseSensitive(m, "orbit");
	if (orbit && (oem || aem))
		return review_bad(err, p, "mission", NULL, "give the OEM/AEM files or an orbit, not both");
	if (orbit) {
		p->mission = REVIEW_MISSION_ORBIT;
		snprintf(p->attitude, sizeof(p->attitude), "nadir");
		rc = string(p, m, "attitude", p->attitude, sizeof(p->attitude), err);
		if (rc == STRAY_OK && strcmp(p->attitude, "nadir") &&
		    strcmp(p->attitude, "inertial") && strcmp(p->attitude, "sun"))
			return review_bad(err, p, "mission.attitude", p->attitude,
				   "must be nadir, inertial or sun");
		return rc == STRAY_OK ? take_orbit(p, orbit, err) : rc;
	}
	if (!oem || !aem || cJSON_GetObjectItemCaseSensitive(m, "attitude"))
		return review_bad(err, p, "mission", NULL,
			   "must be {\"oem\": F, \"aem\": F} or {\"orbit\": {...}, \"attitude\": A}");
	if (!cJSON_IsString(oem) || !cJSON_IsString(aem))
		return review_bad(err, p, "mission", NULL, "oem and aem must be file names");
	p->mission = REVIEW_MISSION_FILES;
	if (!join(p, oem->valuestring, p->oem) || !join(p, aem->valuestring, p->aem))
		return review_bad(err, p, "mission", NULL, "path too long");
	return STRAY_OK;
}

static int vec3(const struct review_project *p, const cJSON *h,
		const char *key, double v[3], struct stray_error *err)
{
	const cJSON *a = cJSON_GetObjectItemCaseSensitive(h, key), *x;
	int i = 0;

	if (!cJSON_IsArray(a) || cJSON_GetArraySize(a) != 3)
		return review_bad(err, p, key, NULL, "must be [x, y, z]");
	cJSON_ArrayForEach(x, a) {
		if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble))
			return review_bad(err, p, key, NULL, "must be 3 numbers");
		v[i++] = x->valuedouble;
	}
	if (fabs(v[0]) + fabs(v[1]) + fabs(v[2]) == 0.0)
		return review_bad(err, p, key, NULL, "must not be zero");
	return STRAY_OK;
}

int review_take_heads(struct review_project *p, const cJSON *h,
		      struct stray_error *err);
int review_take_heads(struct review_project *p, const cJSON *h,
		      struct stray_error *err)
{
	static const char *const keys[] = { "name", "boresight_body",
					    "up_body", NULL };
	const cJSON *it, *name;
	int rc, i;

	if (!cJSON_IsArray(h) || cJSON_GetArraySize(h) < 1 ||
	    cJSON_GetArraySize(h) > REVIEW_HEADS_MAX)
		return review_bad(err, p, "heads", NULL, "must be a list of 1..8 heads");
	cJSON_ArrayForEach(it, h) {
		struct review_head *hd = &p->head[p->n_heads];

		if (!cJSON_IsObject(it))
			return review_bad(err, p, "heads", NULL, "each head is an object");
		if ((rc = review_only_keys(it, keys, "heads", p, err)) != STRAY_OK)
			return rc;
		name = cJSON_GetObjectItemCaseSensitive(it, "name");
		if (!cJSON_IsString(name) || !name->valuestring[0] ||
		    strlen(name->valuestring) >= sizeof(hd->name) ||
		    strpbrk(name->valuestring, "/\\\"<>&' "))
			return review_bad(err, p, "heads.name", cJSON_IsString(name) ?
				   name->valuestring : NULL,
				   "must be 1..31 characters, no / \\ \" < > & ' or space");
		snprintf(hd->name, sizeof(hd->name), "%s", name->valuestring);
		for (i = 0; i < p->n_heads; i++)
			if (strcmp(p->head[i].name, hd->name) == 0)
				return review_bad(err, p, "heads.name", hd->name, "named twice");
		if ((rc = vec3(p, it, "boresight_body", hd->boresight, err)) ||
		    (rc = vec3(p, it, "up_body", hd->up, err)))
			return rc;
		p->n_heads++;
	}
	return STRAY_OK;
}
