/*
 * lab.c - the lab's devices together (lab.h).  Transient faults
 * (timeouts, disconnects, CRC, a missed target) are retried up to
 * sweep.retries times, reconnecting the device in between; what still
 * fails is returned with the device's own one-line message.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "rig/lab.h"

/* Lamp off, beam blocked, shutter closed (rig_lines_safe through the
 * lab's device table): tries all three, returns the first failure. */
static int lines_safe(struct rig_lab *lab, struct rig_error *err)
{
	int rc_lamp = lab->ops->line_set(lab, RIG_LINE_LAMP, 0, err);
	int rc_beam = lab->ops->line_set(lab, RIG_LINE_BEAM_BLOCK, 1, err);
	int rc_shut = lab->ops->line_set(lab, RIG_LINE_SHUTTER, 0, err);

	if (rc_lamp != RIG_OK)
		return rc_lamp;
	return rc_beam != RIG_OK ? rc_beam : rc_shut;
}

static int open_dev(struct rig_lab *lab, int dev, struct rig_error *err)
{
	int rc = lab->ops->open(lab, dev, err);

	if (rc == RIG_OK)
		lab->open_mask |= 1 << dev;
	return rc;
}

static void close_dev(struct rig_lab *lab, int dev)
{
	if (!(lab->open_mask & (1 << dev)))
		return;
	lab->open_mask &= ~(1 << dev);
	lab->ops->close(lab, dev);
}

int rig_lab_open(struct rig_lab *lab, const struct rig_config *cfg,
		 const struct rig_hal *hal, struct rig_error *err)
{
	int dev, rc = RIG_OK;

	memset(lab, 0, sizeof(*lab));
	lab->cfg = cfg;
	lab->hal = hal;
	lab->ops = strcmp(cfg->backend, "indi") == 0 ? &rig_lab_indi_ops
						       : &rig_lab_native_ops;
	lab->theta_deg = lab->theta_rb_deg = NAN;
	/* Lines first, so the lab is made safe before anything moves. */
	rc = open_dev(lab, RIG_DEV_GPIO, err);
	if (rc == RIG_OK)
		rc = lines_safe(lab, err);
	for (dev = 0; rc == RIG_OK && dev < RIG_DEV_GPIO; dev++)
		if (dev != RIG_DEV_MONITOR || cfg->monitor.enabled)
			rc = open_dev(lab, dev, err);
	if (rc == RIG_OK)
		rc = rig_lab_check(lab, err);
	if (rc != RIG_OK)
		rig_lab_close(lab);
	return rc;
}

void rig_lab_close(struct rig_lab *lab)
{
	int dev;

	for (dev = 0; dev < RIG_DEV_COUNT; dev++)
		close_dev(lab, dev);
	rig_indi_free(lab->indi);
	lab->indi = NULL;
}

int rig_lab_safe(struct rig_lab *lab, struct rig_error *err)
{
	int rc = RIG_OK, r2;

	if (lab->open_mask & (1 << RIG_DEV_GPIO))
		rc = lines_safe(lab, err);
	else
		rc = rig_error_set(err, RIG_EDISCONNECT,
				   "gpio: lines not open; lab state unknown");
	if (lab->open_mask & (1 << RIG_DEV_STAGE)) {
		r2 = lab->ops->stop(lab, err);
		if (rc == RIG_OK)
			rc = r2;
	}
	return rc;
}

int rig_lab_is_safe(const struct rig_lab *lab, char *why, size_t size)
{
	/* The safe level of each line: lamp off, beam blocked, shutter
	 * closed; only a read-back counts. */
	static const int safe_level[RIG_LINE_COUNT] = {
		[RIG_LINE_SHUTTER] = 0, [RIG_LINE_BEAM_BLOCK] = 1,
		[RIG_LINE_LAMP] = 0,
	};
	static const char *const bad[RIG_LINE_COUNT] = {
		[RIG_LINE_SHUTTER] = "shutter open",
		[RIG_LINE_BEAM_BLOCK] = "beam not blocked",
		[RIG_LINE_LAMP] = "lamp on",
	};
	int open = (lab->open_mask & (1 << RIG_DEV_GPIO)) != 0, i, ok = 1;
	size_t n = 0;

	if (size)
		why[0] = '\0';
	for (i = 0; i < RIG_LINE_COUNT; i++) {
		int st = open ? lab->lines.state[i] : -1;
		int w;

		if (st == safe_level[i])
			continue;
		ok = 0;
		if (n >= size)
			continue;
		w = snprintf(why + n, size - n, "%s%s", n ? ", " : "",
			     st < 0 ? "" : bad[i]);
		if (st < 0 && w >= 0 && (size_t)w < size - n)
			w = snprintf(why + n, size - n, "%s%s unknown",
				     n ? ", " : "", rig_line_name(i));
		n += w > 0 ? (size_t)w : 0;
	}
	return ok;
}

int rig_lab_reconnect(struct rig_lab *lab, int dev, struct rig_error *err)
{
	struct rig_error tmp;
	int rc;

	close_dev(lab, dev);
	rig_hal_sleep(lab->hal, 1.0);	/* let the bus settle / replug */
	rig_error_clear(&tmp);
	rc = open_dev(lab, dev, &tmp);
	if (rc == RIG_OK && dev == RIG_DEV_STAGE) {
		lab->theta_deg = lab->theta_rb_deg = NAN;
		rc = lab->ops->home(lab, &tmp);
	}
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "%s", tmp.msg);
	return RIG_OK;
}

static const char *const dev_name[RIG_DEV_COUNT] = {
	[RIG_DEV_STAGE] = "stage", [RIG_DEV_WHEEL] = "wheel",
	[RIG_DEV_CAMERA] = "camera", [RIG_DEV_MONITOR] = "monitor",
	[RIG_DEV_GPIO] = "gpio",
};

static void tell(struct rig_lab *lab, int recovered, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* A fault or a recovery, to whoever listens (the event log). */
static void tell(struct rig_lab *lab, int recovered, const char *fmt, ...)
{
	char msg[RIG_ERROR_MSG_MAX + 80];
	va_list ap;

	if (!lab->on_event)
		return;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	lab->on_event(lab->event_ctx, recovered, msg);
}

/* One device operation; arg carries its parameters. */
typedef int (*lab_op)(struct rig_lab *lab, void *arg, struct rig_error *e);

/* Run op until it succeeds, retrying transient faults (after closing the
 * device, so the next try reconnects) up to sweep.retries times. */
static int with_retries(struct rig_lab *lab, int dev, lab_op op, void *arg,
			struct rig_error *err)
{
	struct rig_error e;
	int n, rc = RIG_OK;

	for (n = 0; n <= lab->cfg->sweep.retries; n++) {
		rig_error_clear(&e);
		rc = RIG_OK;
		if (!(lab->open_mask & (1 << dev)))
			rc = rig_lab_reconnect(lab, dev, &e);
		if (rc == RIG_OK)
			rc = op(lab, arg, &e);
		if (rc == RIG_OK) {
			lab->recoveries += n > 0;
			if (n > 0)
				tell(lab, 1, "%s recovered after %d "
				     "retr%s", dev_name[dev], n,
				     n == 1 ? "y" : "ies");
			return RIG_OK;
		}
		if (!rig_status_is_transient(rc))
			break;
		if (n < lab->cfg->sweep.retries)
			tell(lab, 0, "%s; retry %d of %d%s", e.msg, n + 1,
			     lab->cfg->sweep.retries, rc == RIG_ETARGET
			     ? " after re-homing" : " after reconnecting");
		if (rc != RIG_ETARGET)	/* a miss re-homes instead */
			close_dev(lab, dev);
	}
	return rig_error_set(err, rc, "%s", e.msg);
}

static int home_op(struct rig_lab *lab, void *arg, struct rig_error *e)
{
	(void)arg;
	return lab->ops->home(lab, e);
}

int rig_lab_home(struct rig_lab *lab, struct rig_error *err)
{
	int rc = with_retries(lab, RIG_DEV_STAGE, home_op, NULL, err);

	if (rc == RIG_OK) {
		lab->theta_deg = 0;
		lab->theta_rb_deg = NAN;	/* no position read on homing */
	}
	return rc;
}

static int move_op(struct rig_lab *lab, void *arg, struct rig_error *e)
{
	double theta_deg = *(const double *)arg;
	int rc;

	if (!lab->stage.homed) {
		rc = lab->ops->home(lab, e);
		if (rc != RIG_OK)
			return rc;
	}
	rc = lab->ops->move(lab, theta_deg, e);
	if (rc == RIG_ETARGET)
		lab->stage.homed = 0;	/* re-home before the next try */
	return rc;
}

int rig_lab_move(struct rig_lab *lab, double theta_deg, struct rig_error *err)
{
	const struct rig_stage_cfg *s = &lab->cfg->stage;
	int rc;

	if (!(theta_deg >= s->min_deg && theta_deg <= s->max_deg))
		return rig_error_set(err, RIG_EINTERLOCK,
			"stage: angle %g deg outside limits [%g, %g] deg",
			theta_deg, s->min_deg, s->max_deg);
	lab->theta_deg = lab->theta_rb_deg = NAN;
	rc = with_retries(lab, RIG_DEV_STAGE, move_op, &theta_deg, err);
	if (rc == RIG_OK) {
		lab->theta_deg = theta_deg;
		lab->theta_rb_deg = lab->stage.readback_deg;
	}
	return rc;
}

static int wheel_op(struct rig_lab *lab, void *arg, struct rig_error *e)
{
	return lab->ops->wheel_goto(lab, *(const int *)arg, e);
}

int rig_lab_wheel(struct rig_lab *lab, int slot, struct rig_error *err)
{
	if (lab->wheel.slot == slot && (lab->open_mask & 1 << RIG_DEV_WHEEL))
		return RIG_OK;
	return with_retries(lab, RIG_DEV_WHEEL, wheel_op, &slot, err);
}

int rig_lab_illuminate(struct rig_lab *lab, int frame_type,
		       struct rig_error *err)
{
	int rc;

	/* Table 3.1: dark = no light (shutter shut); ambient = beam blocked
	 * from the aperture; full = beam on the aperture.  The lamp stays on
	 * through a sweep so its drift is not restarted. */
	rc = lab->ops->line_set(lab, RIG_LINE_LAMP, 1, err);
	if (rc == RIG_OK)
		rc = lab->ops->line_set(lab, RIG_LINE_BEAM_BLOCK,
					frame_type != 2, err);
	if (rc == RIG_OK)
		rc = lab->ops->line_set(lab, RIG_LINE_SHUTTER, frame_type != 0,
					err);
	return rc;
}

struct capture_arg {
	double t_exp_s;
	struct rig_image *img;
};

static int capture_op(struct rig_lab *lab, void *arg, struct rig_error *e)
{
	struct capture_arg *a = arg;

	return lab->ops->capture(lab, a->t_exp_s, a->img, e);
}

int rig_lab_capture(struct rig_lab *lab, double t_exp_s,
		    struct rig_image *img, struct rig_error *err)
{
	struct capture_arg a = { t_exp_s, img };

	return with_retries(lab, RIG_DEV_CAMERA, capture_op, &a, err);
}

static int monitor_op(struct rig_lab *lab, void *arg, struct rig_error *e)
{
	return lab->ops->monitor(lab, arg, e);
}

int rig_lab_monitor(struct rig_lab *lab, double *level, struct rig_error *err)
{
	return with_retries(lab, RIG_DEV_MONITOR, monitor_op, level, err);
}
