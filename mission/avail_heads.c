/*
 * avail_heads.c - the heads file of `stray availability`: every key
 * known, every vector finite and non-zero, the up vector off the
 * boresight, names unique.
 */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mission/avail_heads.h"
#include "stray/errfmt.h"
#include "vec3d.h"

static const char name_chars[] =
	"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-";

static int vec3(const cJSON *o, const char *key, double out[3])
{
	const cJSON *arr = cJSON_GetObjectItemCaseSensitive(o, key);
	int k;

	if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) != 3)
		return 0;
	for (k = 0; k < 3; k++) {
		const cJSON *x = cJSON_GetArrayItem(arr, k);

		if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble) ||
		    fabs(x->valuedouble) > 1e6)
			return 0;
		out[k] = x->valuedouble;
	}
	return sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]) > 1e-9;
}

/* The head's frame in the body: +z the boresight, +y the image's up. */
static int head_frame(const double bore[3], const double *up_in,
		      double m[3][3])
{
	double z[3] = { bore[0], bore[1], bore[2] }, up[3], y[3], d;
	int k;

	unit(z);
	if (up_in) {
		memcpy(up, up_in, sizeof(up));
		unit(up);
	} else {	/* the body axis least along the boresight */
		k = fabs(z[0]) < fabs(z[1]) ? (fabs(z[0]) < fabs(z[2]) ? 0 : 2) :
		    (fabs(z[1]) < fabs(z[2]) ? 1 : 2);
		up[0] = up[1] = up[2] = 0.0;
		up[k] = 1.0;
	}
	d = up[0] * z[0] + up[1] * z[1] + up[2] * z[2];
	for (k = 0; k < 3; k++)
		y[k] = up[k] - d * z[k];
	if (sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) < 1e-6)
		return 0;
	unit(y);
	memcpy(m[1], y, sizeof(y));
	memcpy(m[2], z, sizeof(z));
	cross(y, z, m[0]);
	return 1;
}

static int head_fail(struct stray_error *err, const char *file,
		     const char *field, const char *why, const char *text)
{
	stray_error_at(err, STRAY_EPARSE, file, 0, field, why);
	stray_error_text(err, text);
	return STRAY_EPARSE;
}

/* A key no reader knows is refused by name: a misspelt "up_bdy" would
 * otherwise be the default up vector, silently. */
static int only_keys(const cJSON *o, const char *const *keys, const char *file,
		     const char *why, struct stray_error *err)
{
	const cJSON *c;
	size_t i;

	cJSON_ArrayForEach(c, o) {
		int known = 0;

		for (i = 0; keys[i]; i++)
			known |= c->string && strcmp(c->string, keys[i]) == 0;
		if (!known) {
			stray_error_at(err, STRAY_EPARSE, file, 0, "key", why);
			stray_error_text(err, c->string ? c->string : "");
			return STRAY_EPARSE;
		}
	}
	return STRAY_OK;
}

static int one_head(const cJSON *h, const char *path, size_t dirlen,
		    struct avail_head_spec *sp, struct stray_error *err)
{
	static const char *const keys[] = { "name", "boresight_body",
					    "up_body", "table", NULL };
	const cJSON *name = cJSON_GetObjectItemCaseSensitive(h, "name");
	const cJSON *tab = cJSON_GetObjectItemCaseSensitive(h, "table");
	double bore[3], up[3];
	int has_up = cJSON_GetObjectItemCaseSensitive(h, "up_body") != NULL, n;

	if (!cJSON_IsObject(h))
		return head_fail(err, path, "heads", "an entry is not an object", "");
	if (only_keys(h, keys, path,
		      "unknown in a head (name, boresight_body, up_body, table)",
		      err) != STRAY_OK)
		return STRAY_EPARSE;
	if (!cJSON_IsString(name) || !name->valuestring[0] ||
	    strlen(name->valuestring) >= sizeof(sp->name) ||
	    strspn(name->valuestring, name_chars) != strlen(name->valuestring))
		return head_fail(err, path, "name", "not a name of 1..31 letters, digits, _ or -", "");
	if (!vec3(h, "boresight_body", bore))
		return head_fail(err, path, "boresight_body", "not a non-zero [x, y, z]", name->valuestring);
	if (has_up && !vec3(h, "up_body", up))
		return head_fail(err, path, "up_body", "not a non-zero [x, y, z]", name->valuestring);
	if (!head_frame(bore, has_up ? up : NULL, sp->m_bs))
		return head_fail(err, path, "up_body", "along the boresight", name->valuestring);
	if (!cJSON_IsString(tab) || !tab->valuestring[0])
		return head_fail(err, path, "table", "not a file name", name->valuestring);
	snprintf(sp->name, sizeof(sp->name), "%s", name->valuestring);
	n = snprintf(sp->table, sizeof(sp->table), "%.*s%s",
		     tab->valuestring[0] == '/' ? 0 : (int)dirlen, path,
		     tab->valuestring);
	if (n < 0 || (size_t)n >= sizeof(sp->table))
		return head_fail(err, path, "table", "path too long", name->valuestring);
	return STRAY_OK;
}

int avail_heads_parse(const char *buf, size_t len, const char *path,
		      struct avail_head_spec spec[AVAIL_HEADS_MAX], size_t *n,
		      struct stray_error *err)
{
	static const char *const top[] = { "heads", NULL };
	const char *slash = strrchr(path, '/');
	size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0, i = 0, j;
	cJSON *root = cJSON_ParseWithLength(buf, len), *arr, *h;
	int rc = STRAY_OK;

	*n = 0;
	arr = cJSON_GetObjectItemCaseSensitive(root, "heads");
	if (!cJSON_IsObject(root) || !cJSON_IsArray(arr) ||
	    cJSON_GetArraySize(arr) < 1 ||
	    cJSON_GetArraySize(arr) > AVAIL_HEADS_MAX) {
		cJSON_Delete(root);
		return head_fail(err, path, "heads",
				 "not a JSON object with an array of 1..8 heads", "");
	}
	if (only_keys(root, top, path, "unknown at the top (heads)", err) != STRAY_OK) {
		cJSON_Delete(root);
		return STRAY_EPARSE;
	}
	cJSON_ArrayForEach(h, arr) {
		if ((rc = one_head(h, path, dirlen, &spec[i], err)) != STRAY_OK)
			break;
		for (j = 0; j < i && rc == STRAY_OK; j++)
			if (strcmp(spec[j].name, spec[i].name) == 0)
				rc = head_fail(err, path, "name", "given twice",
					       spec[i].name);
		if (rc != STRAY_OK)
			break;
		i++;
	}
	cJSON_Delete(root);
	*n = i;
	return rc;
}
