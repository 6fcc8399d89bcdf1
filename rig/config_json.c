/*
 * config_json.c - the table-driven JSON section parser (config_json.h).
 */
#include <cJSON.h>
#include <stdint.h>
#include <string.h>

#include "rig/config_json.h"

int rig_cfg_bad(struct rig_error *err, const char *name, const char *sec,
		const char *key, const char *why)
{
	return rig_error_set(err, RIG_EPARSE, "%s: %s%s%s: %s", name, sec,
			     *sec ? "." : "", key, why);
}

static int set_field(void *base, const struct rig_cfg_field *f,
		     const cJSON *v, const char *name, const char *sec,
		     struct rig_error *err)
{
	char *p = (char *)base + f->off;
	double d;

	if (f->kind == K_STR) {
		if (!cJSON_IsString(v) || strlen(v->valuestring) > f->max)
			return rig_cfg_bad(err, name, sec, f->key,
				"expected a string of at most 47 bytes");
		strcpy(p, v->valuestring);
		return RIG_OK;
	}
	if (f->kind == K_BOOL) {
		if (!cJSON_IsBool(v))
			return rig_cfg_bad(err, name, sec, f->key,
					   "expected true/false");
		*(int *)p = cJSON_IsTrue(v);
		return RIG_OK;
	}
	if (!cJSON_IsNumber(v))
		return rig_cfg_bad(err, name, sec, f->key, "expected a number");
	d = v->valuedouble;
	if (!(d >= f->min && d <= f->max))
		return rig_error_set(err, RIG_EPARSE,
			"%s: %s.%s: value %g outside [%g, %g]", name, sec,
			f->key, d, f->min, f->max);
	if (f->kind != K_NUM && d != (double)(long)d)
		return rig_cfg_bad(err, name, sec, f->key,
				   "expected an integer");
	if (f->kind == K_NUM)
		*(double *)p = d;
	else if (f->kind == K_INT)
		*(int *)p = (int)d;
	else
		*(uint16_t *)p = (uint16_t)d;
	return RIG_OK;
}

int rig_cfg_apply(void *base, const struct rig_cfg_field *tab,
		  const cJSON *obj, const char *const *extra,
		  const char *name, const char *sec, struct rig_error *err)
{
	const cJSON *v;
	int rc;

	if (!obj)
		return RIG_OK;
	if (!cJSON_IsObject(obj))
		return rig_cfg_bad(err, name, "", sec, "expected an object");
	cJSON_ArrayForEach(v, obj) {
		const struct rig_cfg_field *f;
		const char *const *e;

		for (f = tab; f->key && strcmp(f->key, v->string); f++)
			;
		if (f->key) {
			rc = set_field(base, f, v, name, sec, err);
			if (rc != RIG_OK)
				return rc;
			continue;
		}
		for (e = extra; e && *e && strcmp(*e, v->string); e++)
			;
		if (!e || !*e)
			return rig_cfg_bad(err, name, sec, v->string,
					   "unknown key");
	}
	return RIG_OK;
}

int rig_cfg_num_array(const cJSON *a, double *out, int max, double lo,
		      double hi)
{
	const cJSON *v;
	int n = 0;

	if (!cJSON_IsArray(a))
		return -1;
	cJSON_ArrayForEach(v, a) {
		if (n >= max || !cJSON_IsNumber(v) ||
		    !(v->valuedouble >= lo && v->valuedouble <= hi))
			return -1;
		out[n++] = v->valuedouble;
	}
	return n;
}

int rig_cfg_lookup(const char *const *names, int n, const char *s)
{
	int i;

	for (i = 0; i < n; i++)
		if (s && strcmp(names[i], s) == 0)
			return i;
	return -1;
}
