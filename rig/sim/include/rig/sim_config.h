/*
 * sim_config.h - what only the simulator reads: the virtual lab behind
 * the simulated camera (vlab.h), the fault schedule, and the real delay
 * per simulated frame.  In the config file these are the "vlab" and
 * "sim" sections (docs/rig-config.md); config.c hands them to
 * rig_sim_config_parse.  The real backend ignores them.
 */
#ifndef RIG_SIM_CONFIG_H
#define RIG_SIM_CONFIG_H

#include "rig/status.h"
#include "rig/vlab.h"

#define RIG_FAULTS_MAX 16

enum rig_fault_kind {
	RIG_FAULT_TIMEOUT,	/* reads time out for `count` events */
	RIG_FAULT_DISCONNECT,	/* gone; the next `count` opens fail */
	RIG_FAULT_STALL,	/* accepts commands, never finishes */
	RIG_FAULT_CRC,		/* camera frames corrupted on the wire */
	RIG_FAULT_MISS,		/* stage stops `value` deg short */
	RIG_FAULT_KILL,		/* SIGKILL the process (resume tests) */
	RIG_FAULT_KIND_COUNT
};

/* A fault fires at the at-th event of its device (enum rig_device,
 * 1-based: stage moves, wheel moves, camera triggers, monitor reads, GPIO
 * writes) and lasts `count` events; a disconnect or kill fires once, and
 * `count` re-opens then fail. */
struct rig_fault {
	int device, kind;
	unsigned at, count;
	double value;
};

struct rig_sim_config {
	struct rig_vlab_cfg vlab;
	double real_delay_s;	/* real sleep per simulated frame */
	double monitor_noise;	/* lamp monitor read noise, +- fraction
				 * (uniform; 5e-4 by default) */
	double stage_error_deg;	/* stage settles up to +- this off its
				 * target, within tol_deg (0 by default) */
	int wheel_slots;	/* slots the wheel reports; 0 = as many as
				 * wheel.trans lists (a lab whose wheel has
				 * fewer is refused at start) */
	int n_faults;
	struct rig_fault faults[RIG_FAULTS_MAX];
};

void rig_sim_config_defaults(struct rig_sim_config *sc);

/* Parse the "vlab" and "sim" sections (cJSON objects, NULL = absent) over
 * what sc holds; name is the file, for messages. */
int rig_sim_config_parse(struct rig_sim_config *sc, const void *vlab,
			 const void *sim, const char *name,
			 struct rig_error *err);

/* Parse one fault object {"device","kind","at","count","value"}. */
int rig_sim_fault_parse(const void *json, struct rig_fault *f,
			const char *name, struct rig_error *err);

#endif /* RIG_SIM_CONFIG_H */
