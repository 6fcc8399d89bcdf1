/*
 * sim_devices.h - private to rig/sim: the device side of each byte
 * protocol, one model per device, all above the simulator core
 * (sim_core.h) and below the backend's device table (sim.c).  A model
 * knows only its own state and the core; what the camera needs of the
 * rest of the lab comes in a struct sim_lab_view.
 *
 *   stage    Thorlabs APT unit behind FTDI framing (2 status bytes / 64)
 *   wheel    HID ND wheel (wheel_report.h)
 *   monitor  HID lamp monitor photodiode (monitor_report.h)
 *   camera   frame link (framelink.h), pixels from the virtual lab
 *   lines    shutter, beam block, lamp lines (physical levels)
 */
#ifndef RIG_SIM_DEVICES_H
#define RIG_SIM_DEVICES_H

#include <stddef.h>
#include <stdint.h>

#include "rig/hal.h"
#include "rig/sim_core.h"

/* ---- stage ---- */
struct sim_stage {
	int32_t pos, from, target;
	double t0, t1;		/* motion start and end, virtual s */
	uint32_t moves;		/* absolute moves so far (stage_error_deg) */
	int moving, homing, stalled, open;
	uint8_t in[256];
	size_t in_len;
	uint8_t out[512];
	size_t out_len;
};

void rig_sim_stage_reset(struct sim_stage *s);
int rig_sim_stage_write(struct sim_stage *s, struct rig_sim_core *core,
			const uint8_t *buf, size_t len);
int rig_sim_stage_read(struct sim_stage *s, struct rig_sim_core *core,
		       uint8_t *buf, size_t cap, size_t *got,
		       unsigned timeout_ms);
double rig_sim_stage_angle_deg(const struct sim_stage *s,
			       const struct rig_sim_core *core);

/* ---- ND wheel ---- */
struct sim_wheel {
	int slot, target, open, stalled;
	double t_done;
	int have_report;
	uint8_t report[8];
	uint8_t seq;
};

void rig_sim_wheel_reset(struct sim_wheel *w);
int rig_sim_wheel_write(struct sim_wheel *w, struct rig_sim_core *core,
			const uint8_t *buf, size_t len);
int rig_sim_wheel_read(struct sim_wheel *w, struct rig_sim_core *core,
		       uint8_t *buf, size_t cap, size_t *got,
		       unsigned timeout_ms);
/* Transmission of the slot the wheel is in. */
double rig_sim_wheel_trans(const struct sim_wheel *w,
			   const struct rig_sim_core *core);

/* ---- lamp monitor ---- */
struct sim_monitor {
	int have_report;
	uint8_t report[8];
	uint32_t reads;
};

void rig_sim_monitor_reset(struct sim_monitor *m);
int rig_sim_monitor_write(struct sim_monitor *m, struct rig_sim_core *core,
			  int lamp_on, const uint8_t *buf, size_t len);
int rig_sim_monitor_read(struct sim_monitor *m, struct rig_sim_core *core,
			 uint8_t *buf, size_t cap, size_t *got,
			 unsigned timeout_ms);

/* ---- camera ---- */
/* The lab as the camera sees it when triggered. */
struct sim_lab_view {
	double theta_deg;	/* stage angle */
	double nd_trans;	/* wheel slot transmission */
	int lamp_on, beam_blocked, shutter_open;	/* logical lines */
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

void rig_sim_camera_reset(struct sim_camera *c);
int rig_sim_camera_write(struct sim_camera *c, struct rig_sim_core *core,
			 const struct sim_lab_view *lab, const uint8_t *buf,
			 size_t len);
int rig_sim_camera_read(struct sim_camera *c, struct rig_sim_core *core,
			uint8_t *buf, size_t cap, size_t *got,
			unsigned timeout_ms);
void rig_sim_camera_fini(struct sim_camera *c);

/* ---- GPIO lines ---- */
struct sim_lines {
	int level[RIG_LINE_COUNT];	/* physical levels */
};

/* Power-on levels: every line inactive. */
void rig_sim_lines_init(struct sim_lines *l, const struct rig_sim_core *core);
/* Open the configured line id names; *line is its enum rig_line. */
int rig_sim_lines_open(struct sim_lines *l, struct rig_sim_core *core,
		       const struct rig_gpio_id *id, int *line);
int rig_sim_lines_set(struct sim_lines *l, struct rig_sim_core *core,
		      int line, int value);
int rig_sim_lines_get(const struct sim_lines *l,
		      const struct rig_sim_core *core, int line, int *value);
/* Logical level (active-low undone): 1 = shutter open, blocked, lamp on. */
int rig_sim_lines_logical(const struct sim_lines *l,
			  const struct rig_sim_core *core, int line);

#endif /* RIG_SIM_DEVICES_H */
