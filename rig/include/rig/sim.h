/*
 * sim.h - the simulator backend: the device side of each byte protocol
 * behind the HAL's transfer calls, on a virtual clock, with faults
 * injected on request (config.h: struct rig_fault).
 *
 *   stage   Thorlabs APT unit behind FTDI framing (2 status bytes / 64)
 *   wheel   HID ND wheel (wheel_report.h)
 *   camera  frame link (framelink.h), pixels from the virtual lab
 *   gpio    shutter, beam block, lamp lines (physical levels)
 */
#ifndef RIG_SIM_H
#define RIG_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "rig/config.h"
#include "rig/hal.h"

struct sim_stage {
	int32_t pos, from, target;
	double t0, t1;		/* motion start and end, virtual s */
	int moving, homing, stalled, open;
	uint8_t in[256];
	size_t in_len;
	uint8_t out[512];
	size_t out_len;
};

struct sim_wheel {
	int slot, target, open, stalled;
	double t_done;
	int have_report;
	uint8_t report[8];
	uint8_t seq;
};

struct sim_monitor {
	int have_report;
	uint8_t report[8];
	uint32_t reads;
};

struct sim_camera {
	uint32_t exposure_us;
	struct rig_fl_cmd window;
	uint8_t *clean;		/* last frame as encoded */
	uint8_t *wire;		/* what is being sent now */
	size_t len, sent, cap;
	int queued, open;
	int corrupt_resends;	/* CRC fault with value >= 1 */
	uint32_t frames;
};

struct rig_sim {
	const struct rig_config *cfg;
	double t_s;		/* the virtual clock */
	unsigned events[RIG_SIM_DEVICE_COUNT];
	unsigned open_fail[RIG_SIM_DEVICE_COUNT];	/* opens still to fail */
	int gone[RIG_SIM_DEVICE_COUNT];
	unsigned fault_hits[RIG_FAULTS_MAX];	/* events each fault hit */
	unsigned faults_fired;
	struct sim_stage stage;
	struct sim_wheel wheel;
	struct sim_camera cam;
	struct sim_monitor mon;
	int gpio[RIG_LINE_COUNT];	/* physical levels */
	int gpio_open[RIG_LINE_COUNT];
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

/* ---- private to rig/sim: fault bookkeeping and device sides ---- */
/* Count an event on dev; returns the fault kind active now, or -1. */
int rig_sim_event(struct rig_sim *sim, int dev, double *value);
/* Is a fault of this kind active for dev (without counting)? */
int rig_sim_fault_active(struct rig_sim *sim, int dev, int kind);
void rig_sim_disconnect(struct rig_sim *sim, int dev, unsigned reopen_fails);

int rig_sim_stage_write(struct rig_sim *sim, const uint8_t *buf, size_t len);
int rig_sim_stage_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		   size_t *got, unsigned timeout_ms);
int rig_sim_wheel_write(struct rig_sim *sim, const uint8_t *buf, size_t len);
int rig_sim_wheel_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		   size_t *got, unsigned timeout_ms);
int rig_sim_monitor_write(struct rig_sim *sim, const uint8_t *buf, size_t len);
int rig_sim_monitor_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		     size_t *got, unsigned timeout_ms);
int rig_sim_camera_write(struct rig_sim *sim, const uint8_t *buf, size_t len);
int rig_sim_camera_read(struct rig_sim *sim, uint8_t *buf, size_t cap,
		    size_t *got, unsigned timeout_ms);

#endif /* RIG_SIM_H */
