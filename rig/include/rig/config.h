/*
 * config.h - strayrigd's configuration: a JSON file parsed with cJSON.
 * Every key is optional and falls back to rig_config_defaults(), which
 * describes the simulated lab; a key of the wrong type or out of range is
 * an error naming the file and key.  See docs/rig-config.md.
 */
#ifndef RIG_CONFIG_H
#define RIG_CONFIG_H

#include "rig/devices.h"
#include "rig/status.h"
#include "rig/vlab.h"

#define RIG_PATH_MAX 512
#define RIG_FAULTS_MAX 16

enum rig_sim_device { RIG_SIM_STAGE, RIG_SIM_WHEEL, RIG_SIM_CAMERA,
		      RIG_SIM_MONITOR, RIG_SIM_GPIO, RIG_SIM_DEVICE_COUNT };

enum rig_fault_kind {
	RIG_FAULT_TIMEOUT,	/* reads time out for `count` events */
	RIG_FAULT_DISCONNECT,	/* gone; the next `count` opens fail */
	RIG_FAULT_STALL,	/* accepts commands, never finishes */
	RIG_FAULT_CRC,		/* camera frames corrupted on the wire */
	RIG_FAULT_MISS,		/* stage stops `value` deg short */
	RIG_FAULT_KILL,		/* SIGKILL the process (resume tests) */
	RIG_FAULT_KIND_COUNT
};

/* A fault fires at the at-th event of its device (1-based: stage moves,
 * wheel moves, camera triggers, monitor reads, GPIO writes) and lasts `count` events;
 * a disconnect or kill fires once, and `count` re-opens then fail. */
struct rig_fault {
	int device, kind;
	unsigned at, count;
	double value;
};

struct rig_sweep_cfg {
	double theta_start_deg, theta_stop_deg, theta_step_deg;
	int repeats;		/* frames per (angle, type), thesis: 3 */
	double t_min_s, t_max_s, t_init_s;	/* thesis: 0.01-1 s, 0.1 s */
	double peak_target;	/* fraction of SATLEVEL aimed at */
	int retries;		/* per device operation, then re-home/reopen */
};

struct rig_config {
	char path[RIG_PATH_MAX];	/* file it came from, for messages */
	char backend[16];		/* "sim" or "real" */
	char socket_path[RIG_PATH_MAX];
	int socket_mode;		/* octal permission, default 0600 */
	char socket_group[RIG_NAME_MAX];	/* group owning it, "" = ours */
	struct rig_stage_cfg stage;
	struct rig_wheel_cfg wheel;
	struct rig_line_cfg lines[RIG_LINE_COUNT];
	struct rig_camera_cfg camera;
	struct rig_monitor_cfg monitor;
	struct rig_sweep_cfg sweep;
	struct rig_vlab_cfg vlab;
	double sim_real_delay_s;	/* real sleep per simulated frame */
	int n_faults;
	struct rig_fault faults[RIG_FAULTS_MAX];
};

void rig_config_defaults(struct rig_config *cfg);

/* Parse JSON text over the defaults; name is used in messages. */
int rig_config_parse(struct rig_config *cfg, const char *name,
		     const char *text, struct rig_error *err);

/* Read and parse a file over the defaults. */
int rig_config_load(struct rig_config *cfg, const char *path,
		    struct rig_error *err);

/* Parse one fault object {"device","kind","at","count","value"}. */
int rig_config_fault(const void *json, struct rig_fault *f,
		     const char *name, struct rig_error *err);

#endif /* RIG_CONFIG_H */
