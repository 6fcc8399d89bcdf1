/*
 * devices.h - the lab's device drivers, all above the HAL seam.
 *
 *   rig_stage   rotation stage, Thorlabs APT over the FTDI bridge (libusb)
 *   rig_wheel   ND filter wheel, HID reports (hidapi)
 *   rig_lines   shutter, beam block and lamp enable, GPIO (libgpiod)
 *   rig_camera  tracker camera, frame link over USB bulk (libusb)
 *
 * Each takes its part of the config, returns enum rig_status and writes
 * one line naming the device into a struct rig_error.
 */
#ifndef RIG_DEVICES_H
#define RIG_DEVICES_H

#include <stddef.h>
#include <stdint.h>

#include "rig/framelink.h"
#include "rig/hal.h"
#include "rig/status.h"
#include "rig/wheel_report.h"

#define RIG_NAME_MAX 48

/* The lab's devices, one index for the lab's device table (lab.c), the
 * simulator's (sim.c) and the fault schedule (sim_config.h). */
enum rig_device { RIG_DEV_STAGE, RIG_DEV_WHEEL, RIG_DEV_CAMERA,
		  RIG_DEV_MONITOR, RIG_DEV_GPIO, RIG_DEV_COUNT };

/* "stage", "wheel", "camera", "monitor", "gpio": as in the config file. */
extern const char *const rig_device_names[RIG_DEV_COUNT];

/* ---- rotation stage ---- */
struct rig_stage_cfg {
	struct rig_usb_id usb;
	char serial[RIG_NAME_MAX];
	double counts_per_deg;	/* K10CR1: 49152000 counts / 360 deg */
	double tol_deg;		/* position read-back tolerance */
	double move_timeout_s;
	double min_deg, max_deg;	/* interlock: angle limits */
};

struct rig_stage {
	const struct rig_stage_cfg *cfg;
	const struct rig_hal *hal;
	struct rig_hal_dev usb;
	uint8_t rx[1024];	/* APT bytes received, FTDI status stripped */
	size_t rx_len;
	int homed;
	double readback_deg;	/* position counter after the last move */
};

int rig_stage_open(struct rig_stage *s, const struct rig_hal *hal,
		   const struct rig_stage_cfg *cfg, struct rig_error *err);
int rig_stage_home(struct rig_stage *s, struct rig_error *err);
/* Move and wait; RIG_ETARGET when the read-back misses by > tol_deg. */
int rig_stage_move(struct rig_stage *s, double theta_deg,
		   struct rig_error *err);
int rig_stage_position(struct rig_stage *s, double *theta_deg,
		       struct rig_error *err);
int rig_stage_stop(struct rig_stage *s, struct rig_error *err);
void rig_stage_close(struct rig_stage *s);

/* ---- FTDI bridge under the stage ---- */
int rig_ftdi_setup(struct rig_hal_dev *d, int interface);
/* Bulk IN with the two FTDI status bytes of each 64-byte packet removed. */
int rig_ftdi_read(struct rig_hal_dev *d, uint8_t *buf, size_t cap,
		  size_t *got, unsigned timeout_ms);
int rig_ftdi_write(struct rig_hal_dev *d, const uint8_t *buf, size_t len);

/* ---- ND filter wheel ---- */
struct rig_wheel_cfg {
	uint16_t vid, pid;
	char serial[RIG_NAME_MAX];
	int n_slots;
	double trans[RIG_WHEEL_SLOTS_MAX];	/* slot transmissions, slot 0 clear */
	double move_timeout_s;
};

struct rig_wheel {
	const struct rig_wheel_cfg *cfg;
	const struct rig_hal *hal;
	struct rig_hal_dev hid;
	uint8_t seq;
	int slot;		/* -1 = unknown */
};

int rig_wheel_open(struct rig_wheel *w, const struct rig_hal *hal,
		   const struct rig_wheel_cfg *cfg, struct rig_error *err);
int rig_wheel_goto(struct rig_wheel *w, int slot, struct rig_error *err);
/* The slot count the wheel reports (one QUERY, nothing moves). */
int rig_wheel_count(struct rig_wheel *w, int *n_slots, struct rig_error *err);
void rig_wheel_close(struct rig_wheel *w);

/* ---- lamp monitor photodiode (optional) ---- */
struct rig_monitor_cfg {
	int enabled;
	uint16_t vid, pid;
	char serial[RIG_NAME_MAX];
	double nominal_pa;	/* photocurrent of the nominal lamp: MONITOR 1 */
};

struct rig_monitor {
	const struct rig_monitor_cfg *cfg;
	struct rig_hal_dev hid;
	uint8_t seq;
};

int rig_monitor_open(struct rig_monitor *m, const struct rig_hal *hal,
		     const struct rig_monitor_cfg *cfg, struct rig_error *err);
/* Lamp level relative to nominal (the FITS MONITOR keyword). */
int rig_monitor_read(struct rig_monitor *m, double *level,
		     struct rig_error *err);
void rig_monitor_close(struct rig_monitor *m);

/* ---- GPIO lines ---- */
enum rig_line { RIG_LINE_SHUTTER, RIG_LINE_BEAM_BLOCK, RIG_LINE_LAMP,
		RIG_LINE_COUNT };

struct rig_line_cfg {
	char chip[RIG_NAME_MAX];
	char line[RIG_NAME_MAX];
	int active_low;
};

struct rig_lines {
	const struct rig_line_cfg *cfg;	/* RIG_LINE_COUNT entries */
	struct rig_hal_dev dev[RIG_LINE_COUNT];
	int state[RIG_LINE_COUNT];	/* logical, last read back; -1 unknown */
};

int rig_lines_open(struct rig_lines *l, const struct rig_hal *hal,
		   const struct rig_line_cfg cfg[RIG_LINE_COUNT],
		   struct rig_error *err);
/* Set a line (logical: shutter 1 = open, beam block 1 = blocked, lamp 1 =
 * on) and read it back; RIG_EDEVICE when the read-back disagrees. */
int rig_lines_set(struct rig_lines *l, enum rig_line which, int on,
		  struct rig_error *err);
/* Lamp off, beam blocked, shutter closed; tries all three. */
int rig_lines_safe(struct rig_lines *l, struct rig_error *err);
void rig_lines_close(struct rig_lines *l);
const char *rig_line_name(enum rig_line which);

/* ---- camera ---- */
struct rig_camera_cfg {
	struct rig_usb_id usb;
	char serial[RIG_NAME_MAX];
	int n_rows;
	uint16_t rows[RIG_FL_CMD_ROWS_MAX];
	int col0, n_cols;
	int sat_dn;
	double timeout_s;	/* frame arrival beyond exposure */
	int crc_retries;
};

struct rig_image {
	int n_rows, n_cols, col0;
	uint16_t rows[RIG_FL_CMD_ROWS_MAX];
	uint16_t *px;		/* n_rows * n_cols, caller-owned */
	double t_exp_s;
	uint32_t seq;
	int bits;		/* ADC bits the frame header reports */
};

struct rig_camera {
	const struct rig_camera_cfg *cfg;
	const struct rig_hal *hal;
	struct rig_hal_dev usb;
	uint8_t *buf;		/* one frame on the wire */
	size_t buf_cap;
	uint32_t seq;
	uint32_t exposure_us;
	unsigned crc_rereads;	/* frames re-read after a CRC failure */
	int bits;		/* ADC bits of the last frame; 0 before one */
};

int rig_camera_open(struct rig_camera *c, const struct rig_hal *hal,
		    const struct rig_camera_cfg *cfg, struct rig_error *err);
int rig_camera_set_exposure(struct rig_camera *c, double t_exp_s,
			    struct rig_error *err);
/* Trigger, read and check one frame; a CRC failure is re-read. */
int rig_camera_capture(struct rig_camera *c, struct rig_image *img,
		       struct rig_error *err);
void rig_camera_close(struct rig_camera *c);

#endif /* RIG_DEVICES_H */
