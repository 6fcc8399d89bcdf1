/*
 * sim_core.h - private to rig/sim: the simulator's core, below every
 * device model.  It keeps the virtual clock, counts each device's events
 * against the fault schedule (sim_config.h) and knows which devices the
 * schedule has unplugged.  It knows no device's protocol.
 */
#ifndef RIG_SIM_CORE_H
#define RIG_SIM_CORE_H

#include "rig/config.h"

struct rig_sim_core {
	const struct rig_config *cfg;	/* devices, and cfg->sim */
	double t_s;		/* the virtual clock */
	unsigned events[RIG_DEV_COUNT];
	unsigned open_fail[RIG_DEV_COUNT];	/* opens still to fail */
	int gone[RIG_DEV_COUNT];
	unsigned fault_hits[RIG_FAULTS_MAX];	/* events each fault hit */
	unsigned faults_fired;
};

void rig_sim_core_init(struct rig_sim_core *core,
		       const struct rig_config *cfg);

/* Count an event on dev; returns the fault kind active now, or -1 (and
 * the fault's value in *value).  A disconnect unplugs dev; a kill raises
 * SIGKILL. */
int rig_sim_core_event(struct rig_sim_core *core, int dev, double *value);

/* Is a fault of this kind active for dev (without counting)? */
int rig_sim_core_fault_active(const struct rig_sim_core *core, int dev,
			      int kind);

/* Unplug dev; its next reopen_fails opens fail. */
void rig_sim_core_disconnect(struct rig_sim_core *core, int dev,
			     unsigned reopen_fails);

/* An open of dev: EDISCONNECT while re-opens are still to fail, else
 * plugged in again and RIG_OK. */
int rig_sim_core_open(struct rig_sim_core *core, int dev);

#endif /* RIG_SIM_CORE_H */
