/*
 * config.h - strayrigd's configuration: a JSON file parsed with cJSON.
 * Every key is optional and falls back to rig_config_defaults(), which
 * describes the simulated lab; a key of the wrong type or out of range is
 * an error naming the file and key.  See docs/rig-config.md.  The
 * simulator's sections (virtual lab, fault schedule) are its own type,
 * parsed by rig/sim (sim_config.h).
 */
#ifndef RIG_CONFIG_H
#define RIG_CONFIG_H

#include "rig/devices.h"
#include "rig/indi.h"
#include "rig/sim_config.h"
#include "rig/status.h"

#define RIG_PATH_MAX 512
/* Device locks of the real backend (devlock.h) unless lock_dir says. */
#define RIG_LOCK_DIR_DEFAULT "/run/lock"

/* Angles a sweep may list (theta_list_deg, or theta_ranges_deg in all). */
#define RIG_ANGLE_LIST_MAX 2000
/* Ranges of theta_ranges_deg. */
#define RIG_RANGES_MAX 32

struct rig_sweep_cfg {
	double theta_start_deg, theta_stop_deg, theta_step_deg;
	/* The angles as labs write them, instead of start..stop by step:
	 * an explicit list in the order taken (an angle may come back:
	 * each return is another visit, e.g. 0 deg for the drift), or
	 * ranges [start, stop, step] one after the other.  n_list = 0:
	 * start..stop by step. */
	int n_list;
	double list[RIG_ANGLE_LIST_MAX];
	int list_from_ranges;	/* 1: list came from theta_ranges_deg */
	int repeats;		/* frames per (angle, type), thesis: 3 */
	double t_min_s, t_max_s, t_init_s;	/* thesis: 0.01-1 s, 0.1 s */
	double peak_target;	/* fraction of SATLEVEL aimed at */
	int retries;		/* per device operation, then re-home/reopen */
};

struct rig_config {
	char path[RIG_PATH_MAX];	/* file it came from, for messages */
	char backend[16];		/* "sim", "real" or "indi" */
	char socket_path[RIG_PATH_MAX];
	int socket_mode;		/* octal permission, default 0600 */
	char socket_group[RIG_NAME_MAX];	/* group owning it, "" = ours */
	char lock_dir[RIG_PATH_MAX];	/* device locks (devlock.h); "" none */
	int lock_dir_set;		/* given in the file, not defaulted */
	struct rig_stage_cfg stage;
	struct rig_wheel_cfg wheel;
	struct rig_line_cfg lines[RIG_LINE_COUNT];
	struct rig_camera_cfg camera;
	struct rig_monitor_cfg monitor;
	struct rig_sweep_cfg sweep;
	struct rig_sim_config sim;	/* "vlab" and "sim": rig/sim's own */
	struct rig_indi_cfg indi;	/* "indi": rig/indi's (indi.h) */
};

void rig_config_defaults(struct rig_config *cfg);

/* Parse JSON text over the defaults; name is used in messages. */
int rig_config_parse(struct rig_config *cfg, const char *name,
		     const char *text, struct rig_error *err);

/* Read and parse a file over the defaults. */
int rig_config_load(struct rig_config *cfg, const char *path,
		    struct rig_error *err);

/* The environment's overrides for a lab on one machine: the INDI port
 * from STRAYRIGD_INDI_PORT (scripts/rig-indi.sh starts indiserver on a
 * free port and says which there).  RIG_EINVAL naming a bad value. */
int rig_config_env(struct rig_config *cfg, struct rig_error *err);

#endif /* RIG_CONFIG_H */
