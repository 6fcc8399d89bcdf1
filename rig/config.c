/*
 * config.c - strayrigd's JSON configuration (config.h), parsed by cJSON.
 * Each section has a table of {key, kind, offset, min, max}; unknown keys
 * are errors, so a typo cannot silently leave a default in place.
 */
#include <cJSON.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig/config.h"

enum kind { K_NUM, K_INT, K_U16, K_STR, K_BOOL };

struct field {
	const char *key;
	enum kind kind;
	size_t off;
	double min, max;
};

#define NUM(s, k, lo, hi) { #k, K_NUM, offsetof(s, k), lo, hi }
#define INT(s, k, lo, hi) { #k, K_INT, offsetof(s, k), lo, hi }
#define STR(s, k) { #k, K_STR, offsetof(s, k), 0, RIG_NAME_MAX - 1 }

static const struct field stage_fields[] = {
	{ "vid", K_U16, offsetof(struct rig_stage_cfg, usb.vid), 0, 65535 },
	{ "pid", K_U16, offsetof(struct rig_stage_cfg, usb.pid), 0, 65535 },
	{ "interface", K_INT, offsetof(struct rig_stage_cfg, usb.interface),
	  0, 15 },
	STR(struct rig_stage_cfg, serial),
	NUM(struct rig_stage_cfg, counts_per_deg, 1, 1e9),
	NUM(struct rig_stage_cfg, tol_deg, 1e-6, 10),
	NUM(struct rig_stage_cfg, move_timeout_s, 0.01, 3600),
	NUM(struct rig_stage_cfg, min_deg, -360, 360),
	NUM(struct rig_stage_cfg, max_deg, -360, 360),
	{ NULL, 0, 0, 0, 0 }
};

static const struct field wheel_fields[] = {
	{ "vid", K_U16, offsetof(struct rig_wheel_cfg, vid), 0, 65535 },
	{ "pid", K_U16, offsetof(struct rig_wheel_cfg, pid), 0, 65535 },
	STR(struct rig_wheel_cfg, serial),
	NUM(struct rig_wheel_cfg, move_timeout_s, 0.01, 3600),
	{ NULL, 0, 0, 0, 0 }
};

static const struct field line_fields[] = {
	STR(struct rig_line_cfg, chip),
	STR(struct rig_line_cfg, line),
	{ "active_low", K_BOOL, offsetof(struct rig_line_cfg, active_low), 0,
	  1 },
	{ NULL, 0, 0, 0, 0 }
};

static const struct field camera_fields[] = {
	{ "vid", K_U16, offsetof(struct rig_camera_cfg, usb.vid), 0, 65535 },
	{ "pid", K_U16, offsetof(struct rig_camera_cfg, usb.pid), 0, 65535 },
	{ "interface", K_INT, offsetof(struct rig_camera_cfg, usb.interface),
	  0, 15 },
	STR(struct rig_camera_cfg, serial),
	INT(struct rig_camera_cfg, col0, 0, RIG_FL_SENSOR_COLS - 1),
	INT(struct rig_camera_cfg, n_cols, 1, RIG_FL_SENSOR_COLS),
	INT(struct rig_camera_cfg, sat_dn, 1, 65535),
	NUM(struct rig_camera_cfg, timeout_s, 0.001, 60),
	INT(struct rig_camera_cfg, crc_retries, 0, 100),
	{ NULL, 0, 0, 0, 0 }
};

static const struct field monitor_fields[] = {
	{ "enabled", K_BOOL, offsetof(struct rig_monitor_cfg, enabled), 0, 1 },
	{ "vid", K_U16, offsetof(struct rig_monitor_cfg, vid), 0, 65535 },
	{ "pid", K_U16, offsetof(struct rig_monitor_cfg, pid), 0, 65535 },
	STR(struct rig_monitor_cfg, serial),
	NUM(struct rig_monitor_cfg, nominal_pa, 1, 4e9),
	{ NULL, 0, 0, 0, 0 }
};

static const struct field sweep_fields[] = {
	NUM(struct rig_sweep_cfg, theta_start_deg, -360, 360),
	NUM(struct rig_sweep_cfg, theta_stop_deg, -360, 360),
	NUM(struct rig_sweep_cfg, theta_step_deg, 1e-3, 360),
	INT(struct rig_sweep_cfg, repeats, 1, 1000),
	NUM(struct rig_sweep_cfg, t_min_s, 1e-6, 100),
	NUM(struct rig_sweep_cfg, t_max_s, 1e-6, 100),
	NUM(struct rig_sweep_cfg, t_init_s, 1e-6, 100),
	NUM(struct rig_sweep_cfg, peak_target, 0.1, 0.99),
	INT(struct rig_sweep_cfg, retries, 0, 100),
	{ NULL, 0, 0, 0, 0 }
};

static const struct field vlab_fields[] = {
	NUM(struct rig_vlab_cfg, lamp_rate_dn_s, 0, 1e12),
	NUM(struct rig_vlab_cfg, lamp_drift_per_h, -1, 1),
	NUM(struct rig_vlab_cfg, lens_scale_deg, 1e-3, 1e3),
	NUM(struct rig_vlab_cfg, lens_floor, 0, 1),
	NUM(struct rig_vlab_cfg, gradient, -1, 1),
	NUM(struct rig_vlab_cfg, ambient_dn_s, 0, 1e9),
	NUM(struct rig_vlab_cfg, atmos_frac, 0, 1),
	NUM(struct rig_vlab_cfg, dark_dn_s, 0, 1e9),
	NUM(struct rig_vlab_cfg, read_noise_dn, 0, 1e4),
	NUM(struct rig_vlab_cfg, gain_e_per_dn, 1e-3, 1e3),
	NUM(struct rig_vlab_cfg, hot_frac, 0, 1),
	NUM(struct rig_vlab_cfg, hot_dn_s, 0, 1e9),
	INT(struct rig_vlab_cfg, sat_dn, 1, 65535),
	{ NULL, 0, 0, 0, 0 }
};

static const struct field ghost_fields[] = {
	NUM(struct rig_ghost, amp, 0, 10),
	NUM(struct rig_ghost, col_at0, -1e5, 1e5),
	NUM(struct rig_ghost, px_per_deg, -1e4, 1e4),
	NUM(struct rig_ghost, sigma_px, 1e-3, 1e5),
	NUM(struct rig_ghost, theta_c_deg, -360, 360),
	NUM(struct rig_ghost, theta_w_deg, 1e-3, 1e3),
	{ NULL, 0, 0, 0, 0 }
};

static int bad(struct rig_error *err, const char *name, const char *sec,
	       const char *key, const char *why)
{
	return rig_error_set(err, RIG_EPARSE, "%s: %s%s%s: %s", name, sec,
			     *sec ? "." : "", key, why);
}

static int set_field(void *base, const struct field *f, const cJSON *v,
		     const char *name, const char *sec, struct rig_error *err)
{
	char *p = (char *)base + f->off;
	double d;

	if (f->kind == K_STR) {
		if (!cJSON_IsString(v) || strlen(v->valuestring) > f->max)
			return bad(err, name, sec, f->key,
				   "expected a string of at most 47 bytes");
		strcpy(p, v->valuestring);
		return RIG_OK;
	}
	if (f->kind == K_BOOL) {
		if (!cJSON_IsBool(v))
			return bad(err, name, sec, f->key, "expected true/false");
		*(int *)p = cJSON_IsTrue(v);
		return RIG_OK;
	}
	if (!cJSON_IsNumber(v))
		return bad(err, name, sec, f->key, "expected a number");
	d = v->valuedouble;
	if (!(d >= f->min && d <= f->max))
		return rig_error_set(err, RIG_EPARSE,
			"%s: %s.%s: value %g outside [%g, %g]", name, sec,
			f->key, d, f->min, f->max);
	if (f->kind != K_NUM && d != (double)(long)d)
		return bad(err, name, sec, f->key, "expected an integer");
	if (f->kind == K_NUM)
		*(double *)p = d;
	else if (f->kind == K_INT)
		*(int *)p = (int)d;
	else
		*(uint16_t *)p = (uint16_t)d;
	return RIG_OK;
}

/* Apply a section: table keys first; `extra` lists keys handled by the
 * caller; anything else is an unknown key. */
static int apply(void *base, const struct field *tab, const cJSON *obj,
		 const char *const *extra, const char *name, const char *sec,
		 struct rig_error *err)
{
	const cJSON *v;
	int rc;

	if (!obj)
		return RIG_OK;
	if (!cJSON_IsObject(obj))
		return bad(err, name, "", sec, "expected an object");
	cJSON_ArrayForEach(v, obj) {
		const struct field *f;
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
			return bad(err, name, sec, v->string, "unknown key");
	}
	return RIG_OK;
}

/* A JSON array of numbers into out[0..max); returns the count or -1. */
static int num_array(const cJSON *a, double *out, int max, double lo,
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

static int parse_wheel(struct rig_config *cfg, const cJSON *o,
		       const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "trans", NULL };
	const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "trans");
	int rc = apply(&cfg->wheel, wheel_fields, o, extra, name, "wheel",
		       err);

	if (rc != RIG_OK || !t)
		return rc;
	rc = num_array(t, cfg->wheel.trans, RIG_WHEEL_SLOTS_MAX, 1e-12, 1);
	if (rc < 1)
		return bad(err, name, "wheel", "trans",
			   "expected 1-12 transmissions in (0, 1]");
	cfg->wheel.n_slots = rc;
	return RIG_OK;
}

static int parse_camera(struct rig_config *cfg, const cJSON *o,
			const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "rows", NULL };
	const cJSON *r = cJSON_GetObjectItemCaseSensitive(o, "rows");
	double rows[RIG_FL_CMD_ROWS_MAX];
	int rc = apply(&cfg->camera, camera_fields, o, extra, name, "camera",
		       err);
	int i, n;

	if (rc != RIG_OK || !r)
		return rc;
	n = num_array(r, rows, RIG_FL_CMD_ROWS_MAX, 0, RIG_FL_SENSOR_ROWS - 1);
	for (i = 1; i < n; i++)
		if (rows[i] <= rows[i - 1])
			n = -1;
	if (n < 1)
		return bad(err, name, "camera", "rows",
			   "expected 1-24 increasing row indices < 1944");
	cfg->camera.n_rows = n;
	for (i = 0; i < n; i++)
		cfg->camera.rows[i] = (uint16_t)rows[i];
	return RIG_OK;
}

static int parse_vlab(struct rig_config *cfg, const cJSON *o,
		      const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "bias_dn", "ghosts", "seed",
					     NULL };
	const cJSON *b = cJSON_GetObjectItemCaseSensitive(o, "bias_dn");
	const cJSON *g = cJSON_GetObjectItemCaseSensitive(o, "ghosts");
	const cJSON *s = cJSON_GetObjectItemCaseSensitive(o, "seed");
	const cJSON *v;
	int rc = apply(&cfg->vlab, vlab_fields, o, extra, name, "vlab", err);

	if (rc != RIG_OK)
		return rc;
	if (b && num_array(b, cfg->vlab.bias_dn, RIG_VLAB_CHANNELS, 0,
			   65535) != RIG_VLAB_CHANNELS)
		return bad(err, name, "vlab", "bias_dn",
			   "expected 8 channel offsets in DN");
	if (s && !(cJSON_IsNumber(s) && s->valuedouble >= 0))
		return bad(err, name, "vlab", "seed", "expected an integer");
	if (s)
		cfg->vlab.seed = (uint64_t)s->valuedouble;
	if (!g)
		return RIG_OK;
	if (!cJSON_IsArray(g) || cJSON_GetArraySize(g) > RIG_VLAB_GHOSTS_MAX)
		return bad(err, name, "vlab", "ghosts",
			   "expected a list of at most 4 ghosts");
	cfg->vlab.n_ghosts = 0;
	cJSON_ArrayForEach(v, g) {
		struct rig_ghost *gh = &cfg->vlab.ghost[cfg->vlab.n_ghosts++];

		rc = apply(gh, ghost_fields, v, NULL, name, "vlab.ghosts",
			   err);
		if (rc != RIG_OK)
			return rc;
	}
	return RIG_OK;
}

static int lookup(const char *const *names, int n, const char *s)
{
	int i;

	for (i = 0; i < n; i++)
		if (s && strcmp(names[i], s) == 0)
			return i;
	return -1;
}

int rig_config_fault(const void *json, struct rig_fault *f, const char *name,
		     struct rig_error *err)
{
	static const char *const devs[] = { "stage", "wheel", "camera",
					    "monitor", "gpio" };
	static const char *const kinds[] = { "timeout", "disconnect", "stall",
					     "crc", "miss", "kill" };
	static const struct field tab[] = {
		{ "at", K_INT, offsetof(struct rig_fault, at), 1, 1e9 },
		{ "count", K_INT, offsetof(struct rig_fault, count), 1, 1e9 },
		NUM(struct rig_fault, value, -360, 360),
		{ NULL, 0, 0, 0, 0 }
	};
	static const char *const extra[] = { "device", "kind", NULL };
	const cJSON *o = json;
	int rc;

	memset(f, 0, sizeof(*f));
	f->at = 1;
	f->count = 1;
	f->value = 0.5;
	rc = apply(f, tab, o, extra, name, "sim.faults", err);
	if (rc != RIG_OK)
		return rc;
	f->device = lookup(devs, RIG_SIM_DEVICE_COUNT, cJSON_GetStringValue(
		cJSON_GetObjectItemCaseSensitive(o, "device")));
	f->kind = lookup(kinds, RIG_FAULT_KIND_COUNT, cJSON_GetStringValue(
		cJSON_GetObjectItemCaseSensitive(o, "kind")));
	if (f->device < 0)
		return bad(err, name, "sim.faults", "device",
			   "expected stage, wheel, camera, monitor or gpio");
	if (f->kind < 0)
		return bad(err, name, "sim.faults", "kind",
			   "expected timeout, disconnect, stall, crc, miss "
			   "or kill");
	return RIG_OK;
}

static int parse_sim(struct rig_config *cfg, const cJSON *o, const char *name,
		     struct rig_error *err)
{
	static const char *const extra[] = { "faults", NULL };
	static const struct field tab[] = {
		{ "real_delay_s", K_NUM,
		  offsetof(struct rig_config, sim_real_delay_s), 0, 10 },
		{ NULL, 0, 0, 0, 0 }
	};
	const cJSON *fl = cJSON_GetObjectItemCaseSensitive(o, "faults");
	const cJSON *v;
	int rc = apply(cfg, tab, o, extra, name, "sim", err);

	if (rc != RIG_OK || !fl)
		return rc;
	if (!cJSON_IsArray(fl) || cJSON_GetArraySize(fl) > RIG_FAULTS_MAX)
		return bad(err, name, "sim", "faults",
			   "expected a list of at most 16 faults");
	cfg->n_faults = 0;
	cJSON_ArrayForEach(v, fl) {
		rc = rig_config_fault(v, &cfg->faults[cfg->n_faults++], name,
				      err);
		if (rc != RIG_OK)
			return rc;
	}
	return RIG_OK;
}

static int parse_gpio(struct rig_config *cfg, const cJSON *o,
		      const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "shutter", "beam_block", "lamp",
					     NULL };
	static const struct field none[] = { { NULL, 0, 0, 0, 0 } };
	int i, rc = apply(cfg, none, o, extra, name, "gpio", err);

	for (i = 0; rc == RIG_OK && i < RIG_LINE_COUNT; i++)
		rc = apply(&cfg->lines[i], line_fields,
			   cJSON_GetObjectItemCaseSensitive(o, extra[i]),
			   NULL, name, extra[i], err);
	return rc;
}

static int parse_top(struct rig_config *cfg, const cJSON *root,
		     const char *name, struct rig_error *err)
{
	static const char *const extra[] = {
		"backend", "socket", "socket_mode", "socket_group", "stage",
		"wheel", "gpio",
		"camera", "monitor", "sweep", "vlab", "sim", NULL
	};
	static const struct field tab[] = {
		{ "socket_mode", K_INT, offsetof(struct rig_config, socket_mode),
		  0, 0777 },
		{ "socket_group", K_STR, offsetof(struct rig_config,
						  socket_group), 0,
		  RIG_NAME_MAX - 1 },
		{ NULL, 0, 0, 0, 0 }
	};
	const cJSON *v;
	int rc = apply(cfg, tab, root, extra, name, "", err);

#define SECTION(k) cJSON_GetObjectItemCaseSensitive(root, k)
	if (rc == RIG_OK && (v = SECTION("backend")) != NULL) {
		const char *b = cJSON_GetStringValue(v);

		if (!b || (strcmp(b, "sim") && strcmp(b, "real")))
			return bad(err, name, "", "backend",
				   "expected \"sim\" or \"real\"");
		strcpy(cfg->backend, b);
	}
	if (rc == RIG_OK && (v = SECTION("socket")) != NULL) {
		const char *p = cJSON_GetStringValue(v);

		if (!p || strlen(p) >= 100)
			return bad(err, name, "", "socket",
				   "expected a path shorter than 100 bytes");
		strcpy(cfg->socket_path, p);
	}
	if (rc == RIG_OK)
		rc = apply(&cfg->stage, stage_fields, SECTION("stage"), NULL,
			   name, "stage", err);
	if (rc == RIG_OK)
		rc = parse_wheel(cfg, SECTION("wheel"), name, err);
	if (rc == RIG_OK)
		rc = parse_gpio(cfg, SECTION("gpio"), name, err);
	if (rc == RIG_OK)
		rc = parse_camera(cfg, SECTION("camera"), name, err);
	if (rc == RIG_OK)
		rc = apply(&cfg->monitor, monitor_fields, SECTION("monitor"),
			   NULL, name, "monitor", err);
	if (rc == RIG_OK)
		rc = apply(&cfg->sweep, sweep_fields, SECTION("sweep"), NULL,
			   name, "sweep", err);
	if (rc == RIG_OK)
		rc = parse_vlab(cfg, SECTION("vlab"), name, err);
	if (rc == RIG_OK)
		rc = parse_sim(cfg, SECTION("sim"), name, err);
#undef SECTION
	return rc;
}

/* Cross-field checks the per-key ranges cannot express. */
static int check(const struct rig_config *c, const char *name,
		 struct rig_error *err)
{
	const struct rig_sweep_cfg *s = &c->sweep;

	if (c->stage.min_deg >= c->stage.max_deg)
		return bad(err, name, "stage", "min_deg", "not below max_deg");
	if (s->theta_start_deg > s->theta_stop_deg ||
	    s->theta_start_deg < c->stage.min_deg ||
	    s->theta_stop_deg > c->stage.max_deg)
		return bad(err, name, "sweep", "theta_stop_deg",
			   "sweep range not inside the stage limits");
	if (!(s->t_min_s <= s->t_init_s && s->t_init_s <= s->t_max_s))
		return bad(err, name, "sweep", "t_init_s",
			   "need t_min_s <= t_init_s <= t_max_s");
	if (c->camera.n_cols * 2 + 2 > 65535 * 2 ||
	    c->camera.col0 + c->camera.n_cols > RIG_FL_SENSOR_COLS)
		return bad(err, name, "camera", "n_cols",
			   "window runs past column 2592");
	return RIG_OK;
}

int rig_config_parse(struct rig_config *cfg, const char *name,
		     const char *text, struct rig_error *err)
{
	cJSON *root = cJSON_Parse(text);
	int rc;

	if (!root) {
		const char *at = cJSON_GetErrorPtr();

		return rig_error_set(err, RIG_EPARSE,
			"%s: not valid JSON near '%.20s'", name,
			at ? at : "");
	}
	if (!cJSON_IsObject(root))
		rc = bad(err, name, "", "(top)", "expected a JSON object");
	else
		rc = parse_top(cfg, root, name, err);
	cJSON_Delete(root);
	if (rc == RIG_OK)
		rc = check(cfg, name, err);
	return rc;
}

int rig_config_load(struct rig_config *cfg, const char *path,
		    struct rig_error *err)
{
	FILE *f = fopen(path, "rb");
	char *text;
	long n;
	int rc;

	if (!f)
		return rig_error_set(err, RIG_EIO, "%s: cannot open", path);
	fseek(f, 0, SEEK_END);
	n = ftell(f);
	rewind(f);
	if (n < 0 || n > (1L << 20)) {
		fclose(f);
		return rig_error_set(err, RIG_EPARSE, "%s: not a config "
				     "(size %ld)", path, n);
	}
	text = calloc(1, (size_t)n + 1);
	if (!text || fread(text, 1, (size_t)n, f) != (size_t)n) {
		free(text);
		fclose(f);
		return rig_error_set(err, RIG_EIO, "%s: cannot read", path);
	}
	fclose(f);
	snprintf(cfg->path, sizeof(cfg->path), "%s", path);
	rc = rig_config_parse(cfg, path, text, err);
	free(text);
	return rc;
}
