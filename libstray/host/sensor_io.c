/*
 * sensor_io.c - sensors by name or from JSON (cJSON).
 */
#include <cJSON.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/detector.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sensor_io.h"

enum key_kind { KEY_NUMBER, KEY_NAME, KEY_SPECTRUM, KEY_DETECTOR };

struct sensor_key {
	const char *key;
	enum key_kind kind;
	size_t offset;
};

#define NUM(f) { #f, KEY_NUMBER, offsetof(struct stray_sensor, f) }
#define SPEC(f) { #f, KEY_SPECTRUM, offsetof(struct stray_sensor, f) }

static const struct sensor_key keys[] = {
	{ "name", KEY_NAME, offsetof(struct stray_sensor, name) },
	NUM(pixels_x), NUM(pixels_y), NUM(pixel_pitch_um), NUM(t_exp_s),
	NUM(aperture_diameter_mm), NUM(star_window_px), NUM(drs_mag),
	NUM(pr_drs), NUM(fdr_tolerated), NUM(fov_half_deg),
	NUM(read_noise_e), NUM(dark_current_e_s), NUM(vega_mag),
	NUM(moon_mag), SPEC(qe), SPEC(sun), SPEC(vega),
	{ "detector", KEY_DETECTOR, offsetof(struct stray_sensor, detector) },
	NUM(detector_sigma), NUM(min_stars),
};

#define N_KEYS (sizeof(keys) / sizeof(keys[0]))

static const struct sensor_key *find_key(const char *name)
{
	size_t i;

	for (i = 0; i < N_KEYS; i++)
		if (strcmp(keys[i].key, name) == 0)
			return &keys[i];
	return NULL;
}

/* A spectrum source: built-in names as they are, paths from base_dir. */
static int set_spectrum(char *dst, const char *src, const char *base_dir)
{
	int n;

	if (strncmp(src, "builtin:", 8) == 0 || src[0] == '/' || !base_dir ||
	    !base_dir[0])
		n = snprintf(dst, STRAY_PATH_MAX, "%s", src);
	else
		n = snprintf(dst, STRAY_PATH_MAX, "%s/%s", base_dir, src);
	return n >= 0 && n < STRAY_PATH_MAX;
}

static int take_item(const char *name, const cJSON *item,
		     const char *base_dir, struct stray_sensor *s,
		     struct stray_error *err)
{
	const struct sensor_key *k = find_key(item->string);
	char *field;

	if (!k) {
		stray_error_at(err, STRAY_ENOTFOUND, name, 0, "sensor key",
			       "unknown (see docs/formats.md)");
		stray_error_text(err, item->string);
		return STRAY_ENOTFOUND;
	}
	field = (char *)s + k->offset;
	if (k->kind == KEY_NUMBER) {
		if (!cJSON_IsNumber(item)) {
			stray_error_at(err, STRAY_EINVAL, name, 0, k->key,
				       "must be a number");
			return STRAY_EINVAL;
		}
		*(double *)(void *)field = item->valuedouble;
		return STRAY_OK;
	}
	if (!cJSON_IsString(item))
		return stray_error_at(err, STRAY_EINVAL, name, 0, k->key,
				      "must be a string");
	if (k->kind == KEY_DETECTOR) {
		enum stray_detector_kind d;

		if (stray_detector_parse(item->valuestring, &d, NULL) != STRAY_OK) {
			stray_error_at(err, STRAY_EINVAL, name, 0, k->key,
				"must be thesis, window, threshold or tetra3");
			stray_error_text(err, item->valuestring);
			return STRAY_EINVAL;
		}
		snprintf(field, sizeof(s->detector), "%s", item->valuestring);
		return STRAY_OK;
	}
	if (k->kind == KEY_NAME) {
		snprintf(field, STRAY_NAME_MAX, "%s", item->valuestring);
		return STRAY_OK;
	}
	if (!set_spectrum(field, item->valuestring, base_dir))
		return stray_error_at(err, STRAY_EINVAL, name, 0, k->key,
				      "path too long");
	return STRAY_OK;
}

int stray_sensor_parse(const char *name, const char *text,
		       const char *base_dir, struct stray_sensor *s,
		       struct stray_error *err)
{
	cJSON *root = cJSON_Parse(text), *item;
	int rc = STRAY_OK;

	*s = *stray_sensor_st16_like();
	if (!root || !cJSON_IsObject(root)) {
		const char *at = cJSON_GetErrorPtr();

		stray_error_at(err, STRAY_EPARSE, name, 0, "json",
			       root ? "top level must be an object"
				    : "malformed JSON");
		if (!root && at)
			stray_error_text(err, at);
		cJSON_Delete(root);
		return STRAY_EPARSE;
	}
	cJSON_ArrayForEach(item, root) {
		rc = take_item(name, item, base_dir, s, err);
		if (rc != STRAY_OK)
			break;
	}
	cJSON_Delete(root);
	if (rc == STRAY_OK && (rc = stray_sensor_check(s, err)) != STRAY_OK)
		stray_error_locate(err, name, 0);
	return rc;
}

int stray_sensor_load(const char *spec, struct stray_sensor *s,
		      struct stray_error *err)
{
	const struct stray_sensor *st16 = stray_sensor_st16_like();
	char *text, dir[STRAY_PATH_MAX];
	const char *slash;
	size_t len;
	int rc;

	if (strcmp(spec, st16->name) == 0) {
		*s = *st16;
		return STRAY_OK;
	}
	if (!strchr(spec, '/') && !strstr(spec, ".json")) {
		stray_error_set(err, STRAY_ENOTFOUND, "sensor",
			"is neither a built-in sensor (st16-like) nor a JSON file");
		stray_error_text(err, spec);
		return STRAY_ENOTFOUND;
	}
	rc = stray_file_read(spec, &text, &len, err);
	if (rc != STRAY_OK)
		return rc;
	slash = strrchr(spec, '/');
	snprintf(dir, sizeof(dir), "%.*s", slash ? (int)(slash - spec) : 0,
		 spec);
	rc = stray_sensor_parse(spec, text, dir, s, err);
	free(text);
	return rc;
}
