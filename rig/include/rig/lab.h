/*
 * lab.h - the lab as one object: stage, ND wheel, GPIO lines and camera
 * opened on one HAL, with the interlocks and recovery the sweep and the
 * daemon share.  Safe state: lamp off, beam blocked, shutter closed,
 * stage stopped (rig_lab_safe, called on abort, fault, signal and exit).
 */
#ifndef RIG_LAB_H
#define RIG_LAB_H

#include "rig/config.h"
#include "rig/devices.h"
#include "rig/indi.h"
#include <stddef.h>

struct rig_lab;

/* The lab's devices by backend: the native drivers (lab_native.c) or an
 * indiserver's (rig/indi/indi_lab.c).  lab.c keeps the retries,
 * interlocks and safe state above them.  dev is an enum rig_device; the
 * INDI lab's RIG_DEV_GPIO is its lamp, beam block and shutter switches. */
struct rig_lab_ops {
	int (*open)(struct rig_lab *lab, int dev, struct rig_error *err);
	void (*close)(struct rig_lab *lab, int dev);
	int (*home)(struct rig_lab *lab, struct rig_error *err);
	/* Move and read back (lab->stage.readback_deg); RIG_ETARGET when
	 * the read-back misses by more than stage.tol_deg. */
	int (*move)(struct rig_lab *lab, double theta_deg,
		    struct rig_error *err);
	int (*stop)(struct rig_lab *lab, struct rig_error *err);
	int (*wheel_goto)(struct rig_lab *lab, int slot, struct rig_error *err);
	int (*wheel_count)(struct rig_lab *lab, int *n, struct rig_error *err);
	/* Set a line and read it back into lab->lines.state[which]. */
	int (*line_set)(struct rig_lab *lab, enum rig_line which, int on,
			struct rig_error *err);
	int (*capture)(struct rig_lab *lab, double t_exp_s,
		       struct rig_image *img, struct rig_error *err);
	int (*monitor)(struct rig_lab *lab, double *level,
		       struct rig_error *err);
};

extern const struct rig_lab_ops rig_lab_native_ops;
extern const struct rig_lab_ops rig_lab_indi_ops;

/* What the INDI lab read back for the last frame, beside the commanded
 * values (the frame's FILTER/FILTERRB, EXPTIMRB, LAMP/LAMPRB keywords). */
struct rig_lab_readback {
	int valid;		/* 0: a native lab, no such keywords */
	double exptime_s;	/* the BLOB's own EXPTIME */
	int filter_cmd, filter_rb;	/* the device's slot numbers */
	int lamp_cmd, lamp_rb;	/* 1 on, 0 off */
};

struct rig_lab {
	const struct rig_config *cfg;
	const struct rig_lab_ops *ops;
	struct rig_indi *indi;	/* the INDI lab's client, else NULL */
	int indi_cam_fresh;	/* INDI camera (re)connected: window unsent */
	struct rig_lab_readback rb;
	const struct rig_hal *hal;
	struct rig_stage stage;
	struct rig_wheel wheel;
	struct rig_lines lines;
	struct rig_camera camera;
	struct rig_monitor monitor;
	int open_mask;		/* bit per enum rig_device */
	double theta_deg;	/* last commanded and verified; NAN unknown */
	double theta_rb_deg;	/* the stage's read-back there; NAN unknown */
	unsigned recoveries;	/* faults survived by retry or reconnect */
	unsigned crc_rereads;	/* of camera connections already closed */
	/* Told of each fault retried and of each recovery, in words (the
	 * daemon's event log); NULL: nobody listens. */
	void (*on_event)(void *ctx, int recovered, const char *msg);
	void *event_ctx;
};

int rig_lab_open(struct rig_lab *lab, const struct rig_config *cfg,
		 const struct rig_hal *hal, struct rig_error *err);
void rig_lab_close(struct rig_lab *lab);

/* The config against what the devices report (lab_check.c), called by
 * rig_lab_open before anything moves: the wheel's slot count, and two
 * dark test frames at sweep.t_min_s and t_max_s (the window and exposure
 * echoed, camera.sat_dn within the ADC's 2^bits - 1).  RIG_EINVAL names
 * the config key to change. */
int rig_lab_check(struct rig_lab *lab, struct rig_error *err);

/* Lamp off, beam blocked, shutter closed, stage stopped; best effort on
 * every device, returns the first failure. */
int rig_lab_safe(struct rig_lab *lab, struct rig_error *err);

/* 1 when every line has read back its safe level (lamp off, beam
 * blocked, shutter closed); else 0 and why lists each line that is not,
 * "lamp unknown" for one whose state was not read back (a failed write,
 * the GPIO chip gone). */
int rig_lab_is_safe(const struct rig_lab *lab, char *why, size_t size);

/* Close and reopen one device (after a disconnect), re-homing a stage. */
int rig_lab_reconnect(struct rig_lab *lab, int dev, struct rig_error *err);

/* Home the stage, retrying and reconnecting on transient faults. */
int rig_lab_home(struct rig_lab *lab, struct rig_error *err);

/* Move to theta within limits, with retries and re-homing. */
int rig_lab_move(struct rig_lab *lab, double theta_deg,
		 struct rig_error *err);

/* ND slot with retries and reconnects. */
int rig_lab_wheel(struct rig_lab *lab, int slot, struct rig_error *err);

/* Set lines for a frame type: 0 dark, 1 ambient, 2 full. */
int rig_lab_illuminate(struct rig_lab *lab, int frame_type,
		       struct rig_error *err);

/* Exposure and capture with retries and reconnects. */
int rig_lab_capture(struct rig_lab *lab, double t_exp_s,
		    struct rig_image *img, struct rig_error *err);

/* Lamp level from the monitor photodiode (1 = nominal), with retries. */
int rig_lab_monitor(struct rig_lab *lab, double *level, struct rig_error *err);

#endif /* RIG_LAB_H */
