/*
 * config_json.h - the table-driven JSON section parser that config.c and
 * the simulator's sections (rig/sim/sim_config.c) share.  Each section
 * has a table of {key, kind, offset, min, max}; unknown keys are errors,
 * so a typo cannot silently leave a default in place.
 */
#ifndef RIG_CONFIG_JSON_H
#define RIG_CONFIG_JSON_H

#include <cJSON.h>
#include <stddef.h>

#include "rig/status.h"

enum rig_cfg_kind { K_NUM, K_INT, K_U16, K_STR, K_BOOL };

struct rig_cfg_field {
	const char *key;
	enum rig_cfg_kind kind;
	size_t off;
	double min, max;
};

#define NUM(s, k, lo, hi) { #k, K_NUM, offsetof(s, k), lo, hi }
#define INT(s, k, lo, hi) { #k, K_INT, offsetof(s, k), lo, hi }
#define STR(s, k) { #k, K_STR, offsetof(s, k), 0, RIG_NAME_MAX - 1 }

/* "<name>: <sec>.<key>: <why>" as RIG_EPARSE. */
int rig_cfg_bad(struct rig_error *err, const char *name, const char *sec,
		const char *key, const char *why);

/* Apply a section: table keys first; `extra` lists keys handled by the
 * caller; anything else is an unknown key.  A NULL obj is no change. */
int rig_cfg_apply(void *base, const struct rig_cfg_field *tab,
		  const cJSON *obj, const char *const *extra,
		  const char *name, const char *sec, struct rig_error *err);

/* A JSON array of numbers into out[0..max); returns the count or -1. */
int rig_cfg_num_array(const cJSON *a, double *out, int max, double lo,
		      double hi);

/* Index of s in names[0..n), or -1. */
int rig_cfg_lookup(const char *const *names, int n, const char *s);

#endif /* RIG_CONFIG_JSON_H */
