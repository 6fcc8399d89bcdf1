/*
 * config.c - strayrigd's JSON configuration (config.h), parsed by cJSON.
 * Each section has a table of {key, kind, offset, min, max}; unknown keys
 * are errors, so a typo cannot silently leave a default in place.
 */
#include <cJSON.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig/config.h"
#include "rig/config_json.h"

static const struct rig_cfg_field stage_fields[] = {
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

static const struct rig_cfg_field wheel_fields[] = {
	{ "vid", K_U16, offsetof(struct rig_wheel_cfg, vid), 0, 65535 },
	{ "pid", K_U16, offsetof(struct rig_wheel_cfg, pid), 0, 65535 },
	STR(struct rig_wheel_cfg, serial),
	NUM(struct rig_wheel_cfg, move_timeout_s, 0.01, 3600),
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field line_fields[] = {
	STR(struct rig_line_cfg, chip),
	STR(struct rig_line_cfg, line),
	{ "active_low", K_BOOL, offsetof(struct rig_line_cfg, active_low), 0,
	  1 },
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field camera_fields[] = {
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

static const struct rig_cfg_field monitor_fields[] = {
	{ "enabled", K_BOOL, offsetof(struct rig_monitor_cfg, enabled), 0, 1 },
	{ "vid", K_U16, offsetof(struct rig_monitor_cfg, vid), 0, 65535 },
	{ "pid", K_U16, offsetof(struct rig_monitor_cfg, pid), 0, 65535 },
	STR(struct rig_monitor_cfg, serial),
	NUM(struct rig_monitor_cfg, nominal_pa, 1, 4e9),
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field sweep_fields[] = {
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

static int parse_wheel(struct rig_config *cfg, const cJSON *o,
		       const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "trans", NULL };
	const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "trans");
	int rc = rig_cfg_apply(&cfg->wheel, wheel_fields, o, extra, name,
			       "wheel", err);

	if (rc != RIG_OK || !t)
		return rc;
	rc = rig_cfg_num_array(t, cfg->wheel.trans, RIG_WHEEL_SLOTS_MAX,
			       1e-12, 1);
	if (rc < 1)
		return rig_cfg_bad(err, name, "wheel", "trans",
				   "expected 1-12 transmissions in (0, 1]");
	cfg->wheel.n_slots = rc;
	return RIG_OK;
}

/* Ranges [start, stop, step] into the list, start..stop inclusive by
 * step; a range starting where the last ended does not repeat it. */
static int add_ranges(struct rig_sweep_cfg *s, const cJSON *r,
		      const char *name, struct rig_error *err)
{
	const cJSON *t;
	int n = 0;

	if (!cJSON_IsArray(r) || cJSON_GetArraySize(r) < 1 ||
	    cJSON_GetArraySize(r) > RIG_RANGES_MAX)
		return rig_cfg_bad(err, name, "sweep", "theta_ranges_deg",
			"expected 1-32 ranges [start, stop, step] in deg");
	s->n_list = 0;
	cJSON_ArrayForEach(t, r) {
		double v[3];
		long k, count;

		if (rig_cfg_num_array(t, v, 3, -360, 360) != 3 ||
		    !(v[2] >= 1e-3) || v[1] < v[0])
			return rig_cfg_bad(err, name, "sweep",
				"theta_ranges_deg", "each range must be "
				"[start, stop, step] with start <= stop and "
				"step >= 0.001 deg, within -360..360");
		count = (long)floor((v[1] - v[0]) / v[2] + 1e-9) + 1;
		for (k = 0; k < count; k++) {
			double a = v[0] + k * v[2];

			if (s->n_list > 0 && n > 0 && k == 0 &&
			    fabs(a - s->list[s->n_list - 1]) < 1e-9)
				continue;
			if (s->n_list >= RIG_ANGLE_LIST_MAX)
				return rig_cfg_bad(err, name, "sweep",
					"theta_ranges_deg",
					"more than 2000 angles in all");
			s->list[s->n_list++] = a;
		}
		n++;
	}
	s->list_from_ranges = 1;
	return RIG_OK;
}

static int parse_sweep(struct rig_config *cfg, const cJSON *o,
		       const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "theta_list_deg",
					     "theta_ranges_deg", NULL };
	const cJSON *l = cJSON_GetObjectItemCaseSensitive(o, "theta_list_deg");
	const cJSON *r = cJSON_GetObjectItemCaseSensitive(o,
							  "theta_ranges_deg");
	struct rig_sweep_cfg *s = &cfg->sweep;
	int rc = rig_cfg_apply(s, sweep_fields, o, extra, name, "sweep", err);

	if (rc != RIG_OK)
		return rc;
	if (l && r)
		return rig_cfg_bad(err, name, "sweep", "theta_ranges_deg",
				   "give theta_list_deg or theta_ranges_deg, "
				   "not both");
	if (r)
		return add_ranges(s, r, name, err);
	if (!l)
		return RIG_OK;
	rc = rig_cfg_num_array(l, s->list, RIG_ANGLE_LIST_MAX, -360, 360);
	if (rc < 1)
		return rig_cfg_bad(err, name, "sweep", "theta_list_deg",
				   "expected 1-2000 angles in deg, each "
				   "within -360..360");
	s->n_list = rc;
	s->list_from_ranges = 0;
	return RIG_OK;
}

static int parse_camera(struct rig_config *cfg, const cJSON *o,
			const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "rows", NULL };
	const cJSON *r = cJSON_GetObjectItemCaseSensitive(o, "rows");
	double rows[RIG_FL_CMD_ROWS_MAX];
	int rc = rig_cfg_apply(&cfg->camera, camera_fields, o, extra, name,
			       "camera", err);
	int i, n;

	if (rc != RIG_OK || !r)
		return rc;
	n = rig_cfg_num_array(r, rows, RIG_FL_CMD_ROWS_MAX, 0,
			      RIG_FL_SENSOR_ROWS - 1);
	for (i = 1; i < n; i++)
		if (rows[i] <= rows[i - 1])
			n = -1;
	if (n < 1)
		return rig_cfg_bad(err, name, "camera", "rows",
			"expected 1-24 increasing row indices < 1944");
	cfg->camera.n_rows = n;
	for (i = 0; i < n; i++)
		cfg->camera.rows[i] = (uint16_t)rows[i];
	return RIG_OK;
}

static int parse_gpio(struct rig_config *cfg, const cJSON *o,
		      const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "shutter", "beam_block", "lamp",
					     NULL };
	static const struct rig_cfg_field none[] = { { NULL, 0, 0, 0, 0 } };
	int i, rc = rig_cfg_apply(cfg, none, o, extra, name, "gpio", err);

	for (i = 0; rc == RIG_OK && i < RIG_LINE_COUNT; i++)
		rc = rig_cfg_apply(&cfg->lines[i], line_fields,
			cJSON_GetObjectItemCaseSensitive(o, extra[i]), NULL,
			name, extra[i], err);
	return rc;
}

static int parse_top(struct rig_config *cfg, const cJSON *root,
		     const char *name, struct rig_error *err)
{
	static const char *const extra[] = {
		"backend", "socket", "socket_mode", "socket_group",
		"lock_dir", "stage",
		"wheel", "gpio",
		"camera", "monitor", "sweep", "vlab", "sim", "indi", NULL
	};
	static const struct rig_cfg_field tab[] = {
		{ "socket_mode", K_INT, offsetof(struct rig_config, socket_mode),
		  0, 0777 },
		{ "socket_group", K_STR, offsetof(struct rig_config,
						  socket_group), 0,
		  RIG_NAME_MAX - 1 },
		{ NULL, 0, 0, 0, 0 }
	};
	const cJSON *v;
	int rc = rig_cfg_apply(cfg, tab, root, extra, name, "", err);

#define SECTION(k) cJSON_GetObjectItemCaseSensitive(root, k)
	if (rc == RIG_OK && (v = SECTION("backend")) != NULL) {
		const char *b = cJSON_GetStringValue(v);

		if (!b || (strcmp(b, "sim") && strcmp(b, "real") &&
			   strcmp(b, "indi")))
			return rig_cfg_bad(err, name, "", "backend",
				"expected \"sim\", \"real\" or \"indi\"");
		strcpy(cfg->backend, b);
	}
	if (rc == RIG_OK && (v = SECTION("socket")) != NULL) {
		const char *p = cJSON_GetStringValue(v);

		if (!p || strlen(p) >= 100)
			return rig_cfg_bad(err, name, "", "socket",
				"expected a path shorter than 100 bytes");
		strcpy(cfg->socket_path, p);
	}
	if (rc == RIG_OK && (v = SECTION("lock_dir")) != NULL) {
		const char *p = cJSON_GetStringValue(v);

		if (!p || strlen(p) >= 256)
			return rig_cfg_bad(err, name, "", "lock_dir",
				"expected a path shorter than 256 bytes");
		strcpy(cfg->lock_dir, p);
		cfg->lock_dir_set = 1;
	}
	if (rc == RIG_OK)
		rc = rig_cfg_apply(&cfg->stage, stage_fields,
				   SECTION("stage"), NULL, name, "stage", err);
	if (rc == RIG_OK)
		rc = parse_wheel(cfg, SECTION("wheel"), name, err);
	if (rc == RIG_OK)
		rc = parse_gpio(cfg, SECTION("gpio"), name, err);
	if (rc == RIG_OK)
		rc = parse_camera(cfg, SECTION("camera"), name, err);
	if (rc == RIG_OK)
		rc = rig_cfg_apply(&cfg->monitor, monitor_fields,
				   SECTION("monitor"), NULL, name, "monitor",
				   err);
	if (rc == RIG_OK)
		rc = parse_sweep(cfg, SECTION("sweep"), name, err);
	/* The simulator's sections, parsed by rig/sim (sim_config.h). */
	if (rc == RIG_OK)
		rc = rig_sim_config_parse(&cfg->sim, SECTION("vlab"),
					  SECTION("sim"), name, err);
	if (rc == RIG_OK)
		rc = rig_indi_config_parse(&cfg->indi, SECTION("indi"), name,
					   err);
#undef SECTION
	return rc;
}

/* Cross-field checks the per-key ranges cannot express. */
static int check(const struct rig_config *c, const char *name,
		 struct rig_error *err)
{
	const struct rig_sweep_cfg *s = &c->sweep;
	int i;

	if (c->socket_mode & 0002)
		return rig_cfg_bad(err, name, "", "socket_mode",
				   "world-writable (o+w) refused: anyone on "
				   "the machine could drive the lab");
	/* INDI has no lamp monitor of ours: its photodiode is on HID. */
	if (strcmp(c->backend, "indi") == 0 && c->monitor.enabled)
		return rig_cfg_bad(err, name, "monitor", "enabled",
				   "the indi backend has no lamp monitor; "
				   "set it false");
	if (c->stage.min_deg >= c->stage.max_deg)
		return rig_cfg_bad(err, name, "stage", "min_deg",
				   "not below max_deg");
	for (i = 0; i < s->n_list; i++)
		if (s->list[i] < c->stage.min_deg ||
		    s->list[i] > c->stage.max_deg)
			return rig_cfg_bad(err, name, "sweep",
				s->list_from_ranges ? "theta_ranges_deg"
						    : "theta_list_deg",
				"an angle outside the stage limits "
				"[stage.min_deg, stage.max_deg]");
	if (s->n_list == 0 && (s->theta_start_deg > s->theta_stop_deg ||
	    s->theta_start_deg < c->stage.min_deg ||
	    s->theta_stop_deg > c->stage.max_deg))
		return rig_cfg_bad(err, name, "sweep", "theta_stop_deg",
				   "sweep range not inside the stage limits");
	if (!(s->t_min_s <= s->t_init_s && s->t_init_s <= s->t_max_s))
		return rig_cfg_bad(err, name, "sweep", "t_init_s",
				   "need t_min_s <= t_init_s <= t_max_s");
	if (c->camera.n_cols * 2 + 2 > 65535 * 2 ||
	    c->camera.col0 + c->camera.n_cols > RIG_FL_SENSOR_COLS)
		return rig_cfg_bad(err, name, "camera", "n_cols",
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
		rc = rig_cfg_bad(err, name, "", "(top)",
				 "expected a JSON object");
	else
		rc = parse_top(cfg, root, name, err);
	cJSON_Delete(root);
	/* Real devices are locked lab-wide unless told where; a simulated
	 * lab is the daemon's own, so it locks nothing unless told to. */
	if (rc == RIG_OK && !cfg->lock_dir_set)
		strcpy(cfg->lock_dir, strcmp(cfg->backend, "real") == 0
				      ? RIG_LOCK_DIR_DEFAULT : "");
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

int rig_config_env(struct rig_config *cfg, struct rig_error *err)
{
	const char *v = getenv("STRAYRIGD_INDI_PORT");
	char *end;
	long port;

	if (!v)
		return RIG_OK;
	port = strtol(v, &end, 10);
	if (end == v || *end || port < 1 || port > 65535)
		return rig_error_set(err, RIG_EINVAL, "STRAYRIGD_INDI_PORT: "
				     "'%s' is not a port (1-65535)", v);
	cfg->indi.port = (int)port;
	return RIG_OK;
}
