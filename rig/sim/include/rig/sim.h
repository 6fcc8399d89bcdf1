/*
 * sim.h - the simulator backend: the device side of each byte protocol
 * behind the HAL's transfer calls, on a virtual clock, with faults
 * injected on request (sim_config.h: struct rig_fault).
 *
 * Three layers, each calling only the one below:
 *   sim.c            the backend's ops table and its device table (one
 *                    entry per enum rig_device: bus id, open, write, read)
 *   sim_<device>.c   the device models (sim_devices.h)
 *   sim_core.c       virtual clock, event counts, fault schedule
 *                    (sim_core.h)
 */
#ifndef RIG_SIM_H
#define RIG_SIM_H

#include "rig/config.h"
#include "rig/hal.h"
#include "rig/sim_core.h"
#include "rig/sim_devices.h"

struct rig_sim {
	struct rig_sim_core core;	/* clock, faults; core.cfg = cfg */
	struct sim_stage stage;
	struct sim_wheel wheel;
	struct sim_camera cam;
	struct sim_monitor mon;
	struct sim_lines lines;
};

/* Set up a simulator for cfg (kept by pointer) and its HAL. */
int rig_sim_init(struct rig_sim *sim, const struct rig_config *cfg,
		 struct rig_hal *hal);
void rig_sim_fini(struct rig_sim *sim);

/* Logical lab state as the simulator sees it (for tests and the vlab). */
int rig_sim_lamp_on(const struct rig_sim *sim);
int rig_sim_beam_blocked(const struct rig_sim *sim);
int rig_sim_shutter_open(const struct rig_sim *sim);
double rig_sim_angle_deg(const struct rig_sim *sim);

/* Faults the schedule has fired so far. */
unsigned rig_sim_faults_fired(const struct rig_sim *sim);

#endif /* RIG_SIM_H */
