/*
 * plan.c - the sweep's plan, kept in the folder as plan.json (sweep.h):
 * the config values that decide which frames the folder holds and how
 * they compare (angles, repeats, exposure limits and target, camera
 * window and saturation, ND transmissions).  Written atomically (temp,
 * fsync, rename, fsync of the folder) while the folder's lock is held; a
 * resume with other values is refused, naming the first that differs,
 * unless forced, when the new plan replaces the old.
 */
#include <cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rig/sweep.h"

#define PLAN_FILE "plan.json"
#define PLAN_SIZE_MAX 65536

static void add_array(cJSON *o, const char *key, const double *v, int n)
{
	cJSON *a = cJSON_AddArrayToObject(o, key);
	int i;

	for (i = 0; i < n; i++)
		cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
}

/* The plan of a config as one flat JSON object. */
static cJSON *plan_of(const struct rig_config *c)
{
	const struct rig_sweep_cfg *s = &c->sweep;
	cJSON *o = cJSON_CreateObject();
	double rows[RIG_FL_CMD_ROWS_MAX];
	int i;

	for (i = 0; i < c->camera.n_rows; i++)
		rows[i] = c->camera.rows[i];
	cJSON_AddNumberToObject(o, "sweep.theta_start_deg", s->theta_start_deg);
	cJSON_AddNumberToObject(o, "sweep.theta_stop_deg", s->theta_stop_deg);
	cJSON_AddNumberToObject(o, "sweep.theta_step_deg", s->theta_step_deg);
	cJSON_AddNumberToObject(o, "sweep.repeats", s->repeats);
	cJSON_AddNumberToObject(o, "sweep.t_min_s", s->t_min_s);
	cJSON_AddNumberToObject(o, "sweep.t_max_s", s->t_max_s);
	cJSON_AddNumberToObject(o, "sweep.t_init_s", s->t_init_s);
	cJSON_AddNumberToObject(o, "sweep.peak_target", s->peak_target);
	add_array(o, "camera.rows", rows, c->camera.n_rows);
	cJSON_AddNumberToObject(o, "camera.col0", c->camera.col0);
	cJSON_AddNumberToObject(o, "camera.n_cols", c->camera.n_cols);
	cJSON_AddNumberToObject(o, "camera.sat_dn", c->camera.sat_dn);
	add_array(o, "wheel.trans", c->wheel.trans, c->wheel.n_slots);
	/* A list (or ranges) replaces start..stop by step: the angles as
	 * taken, in order; absent otherwise, so older plans still match. */
	if (s->n_list > 0)
		add_array(o, "sweep.theta_list_deg", s->list, s->n_list);
	return o;
}

static int write_all(const char *path, const char *text)
{
	size_t len = strlen(text);
	int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644), ok;

	if (fd < 0)
		return 0;
	ok = write(fd, text, len) == (ssize_t)len &&
	     write(fd, "\n", 1) == 1 && fsync(fd) == 0;
	return close(fd) == 0 && ok;
}

static int plan_write(const char *dir, const cJSON *plan,
		      struct rig_error *err)
{
	char path[RIG_PATH_MAX + 16], tmp[RIG_PATH_MAX + 20];
	char *text = cJSON_Print(plan);
	int ok, fd;

	snprintf(path, sizeof(path), "%s/" PLAN_FILE, dir);
	snprintf(tmp, sizeof(tmp), "%s.tmp", path);
	ok = text && write_all(tmp, text) && rename(tmp, path) == 0;
	free(text);
	if (!ok) {
		unlink(tmp);
		return rig_error_set(err, RIG_EIO, "%s: cannot write", path);
	}
	fd = open(dir, O_RDONLY);	/* the rename, made durable */
	if (fd >= 0) {
		fsync(fd);
		close(fd);
	}
	return RIG_OK;
}

/* The stored plan; NULL when there is none (a folder made before plans
 * were kept, or killed between its manifest and its plan). */
static int plan_read(const char *dir, cJSON **plan, struct rig_error *err)
{
	char path[RIG_PATH_MAX + 16], *text;
	FILE *f;
	long n;

	*plan = NULL;
	snprintf(path, sizeof(path), "%s/" PLAN_FILE, dir);
	if (!(f = fopen(path, "rb")))
		return errno == ENOENT ? RIG_OK
		       : rig_error_set(err, RIG_EIO, "%s: cannot open", path);
	fseek(f, 0, SEEK_END);
	n = ftell(f);
	rewind(f);
	text = n >= 0 && n <= PLAN_SIZE_MAX ? calloc(1, (size_t)n + 1) : NULL;
	if (text && fread(text, 1, (size_t)n, f) == (size_t)n)
		*plan = cJSON_Parse(text);
	free(text);
	fclose(f);
	if (!cJSON_IsObject(*plan)) {
		cJSON_Delete(*plan);
		*plan = NULL;
		return rig_error_set(err, RIG_EPARSE, "%s: not a sweep plan",
				     path);
	}
	return RIG_OK;
}

/* Keys that record who and when, not what: never compared. */
static int is_note(const char *key)
{
	return !strcmp(key, "owner") || !strcmp(key, "created_utc");
}

/* The first key whose value differs between the two plans, or NULL. */
static const char *first_change(const cJSON *was, const cJSON *now)
{
	const cJSON *k;

	cJSON_ArrayForEach(k, now)
		if (!is_note(k->string) &&
		    !cJSON_Compare(k, cJSON_GetObjectItemCaseSensitive(was,
				   k->string), 1))
			return k->string;
	cJSON_ArrayForEach(k, was)
		if (!is_note(k->string) &&
		    !cJSON_GetObjectItemCaseSensitive(now, k->string))
			return k->string;
	return NULL;
}

/* The notes of the plan written: the stored ones kept (the sweep's first
 * owner), else this run's. */
static void add_notes(cJSON *now, const cJSON *was, const char *owner)
{
	const cJSON *o = cJSON_GetObjectItemCaseSensitive(was, "owner");
	const cJSON *c = cJSON_GetObjectItemCaseSensitive(was, "created_utc");
	char when[40];

	rig_utc_stamp(when, sizeof(when));
	cJSON_AddStringToObject(now, "owner", cJSON_IsString(o)
				? o->valuestring : owner ? owner : "?");
	cJSON_AddStringToObject(now, "created_utc", cJSON_IsString(c)
				? c->valuestring : when);
}

static int refuse(const char *dir, const char *key, const cJSON *was,
		  const cJSON *now, struct rig_error *err)
{
	const cJSON *a = cJSON_GetObjectItemCaseSensitive(was, key);
	const cJSON *b = cJSON_GetObjectItemCaseSensitive(now, key);
	char *ta = a ? cJSON_PrintUnformatted(a) : NULL;
	char *tb = b ? cJSON_PrintUnformatted(b) : NULL;

	rig_error_set(err, RIG_EINVAL, "%s/" PLAN_FILE ": %s: the sweep was "
		      "planned with %.40s, the config now gives %.40s; resume "
		      "with --force-plan to accept the change", dir, key,
		      ta ? ta : "nothing", tb ? tb : "nothing");
	free(ta);
	free(tb);
	return RIG_EINVAL;
}

int rig_sweep_plan_check(const char *dir, const struct rig_config *cfg,
			 int force, struct rig_error *err)
{
	return rig_sweep_plan_check_as(dir, cfg, force, NULL, err);
}

int rig_sweep_plan_check_as(const char *dir, const struct rig_config *cfg,
			    int force, const char *owner,
			    struct rig_error *err)
{
	cJSON *now = plan_of(cfg), *was = NULL;
	const char *key;
	int rc = plan_read(dir, &was, err);

	add_notes(now, rc == RIG_OK ? was : NULL, owner);
	if (rc == RIG_OK && was && !force &&
	    (key = first_change(was, now)) != NULL)
		rc = refuse(dir, key, was, now, err);
	else if (rc == RIG_OK && (!was || first_change(was, now)))
		rc = plan_write(dir, now, err);
	if (rc == RIG_EPARSE && force) {	/* forced over a broken plan */
		rig_error_clear(err);
		rc = plan_write(dir, now, err);
	}
	cJSON_Delete(was);
	cJSON_Delete(now);
	return rc;
}
