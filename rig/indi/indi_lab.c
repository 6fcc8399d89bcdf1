/*
 * indi_lab.c - the lab's devices on an indiserver (rig_lab_indi_ops,
 * lab.h): the stage is a rotator's ABS_ROTATOR_ANGLE, the ND wheel a
 * FILTER_SLOT, the lamp and beam block switches (a flat panel's
 * FLAT_LIGHT_CONTROL, a cap or a relay), the shutter the camera's
 * CCD_FRAME_TYPE (light or dark), and frames CCD_EXPOSURE with the image
 * as a FITS BLOB.  Every command waits for the device's own answer (the
 * property back to Ok, its value read back), so a device that did not do
 * it is an error naming the device and property, never believed.  A
 * device disconnected or restarted by indiserver, or the server lost, is
 * RIG_EDISCONNECT: lab.c's retries reconnect it (each operation first
 * connects what is not, indi_props.c), the sweep keeps its frames and
 * resumes.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "indi_props.h"
#include "rig/lab.h"


/* ---- stage ---- */

static int stage_at(struct rig_lab *lab, double theta_deg, double *rb,
		    struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	const char *el[1] = { c->stage.element };
	double v = theta_deg;
	int rc = ilab_property(lab, c->stage.device, c->stage.property,
			  "indi.stage.property", err);

	if (c->stage.wrap360) {
		v = fmod(theta_deg, 360.0);
		v += v < 0 ? 360.0 : 0;
	}
	if (rc == RIG_OK)
		rc = ilab_numbers(lab, c->stage.device, c->stage.property, 1, el,
			     &v, lab->cfg->stage.move_timeout_s, rb, err);
	/* The device's 0..360 back next to the angle asked (-5 = 355). */
	if (rc == RIG_OK && c->stage.wrap360)
		*rb -= 360.0 * round((*rb - theta_deg) / 360.0);
	return rc;
}

static int indi_move(struct rig_lab *lab, double theta_deg,
		     struct rig_error *err)
{
	double rb = NAN;
	int rc = stage_at(lab, theta_deg, &rb, err);

	if (rc != RIG_OK)
		return rc;
	lab->stage.readback_deg = rb;
	if (fabs(rb - theta_deg) > lab->cfg->stage.tol_deg)
		return rig_error_set(err, RIG_ETARGET,
			"stage: '%s' %s: stopped at %.4f deg, target %.4f deg",
			ICFG(lab)->stage.device, ICFG(lab)->stage.property,
			rb, theta_deg);
	return RIG_OK;
}

/* INDI rotators keep their own zero: homing is going to 0 deg and
 * reading it back there. */
static int indi_home(struct rig_lab *lab, struct rig_error *err)
{
	int rc;

	lab->stage.homed = 0;
	rc = indi_move(lab, 0, err);
	lab->stage.homed = rc == RIG_OK;
	return rc;
}

static int indi_stop(struct rig_lab *lab, struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	struct rig_indi_prop p;
	int rc;

	/* Without a server nothing of ours can be moving it. */
	if (!lab->indi || !rig_indi_alive(lab->indi))
		return rig_error_set(err, RIG_EDISCONNECT,
			"stage: '%s': server %s:%d lost; cannot send %s",
			c->stage.device, c->host, c->port, c->stage.abort);
	if (rig_indi_prop(lab->indi, c->stage.device, c->stage.property,
			  &p) != RIG_OK || p.state != RIG_INDI_BUSY)
		return RIG_OK;	/* not moving */
	rc = rig_indi_send_switch(lab->indi, c->stage.device, c->stage.abort,
				  c->stage.abort_element);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "stage: '%s' %s.%s: cannot "
				     "send: %s", c->stage.device,
				     c->stage.abort, c->stage.abort_element,
				     rig_status_text(rc));
	return RIG_OK;
}

/* ---- wheel ---- */

static int indi_wheel_goto(struct rig_lab *lab, int slot,
			   struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	const char *el[1] = { c->wheel.element };
	double want = slot + c->wheel.first_slot, rb = -1;
	int rc;

	lab->wheel.slot = -1;
	if (slot < 0 || slot >= lab->cfg->wheel.n_slots)
		return rig_error_set(err, RIG_EINVAL,
				     "wheel: slot %d outside 0..%d", slot,
				     lab->cfg->wheel.n_slots - 1);
	rc = ilab_property(lab, c->wheel.device, c->wheel.property,
		      "indi.wheel.property", err);
	if (rc == RIG_OK)
		rc = ilab_numbers(lab, c->wheel.device, c->wheel.property, 1, el,
			     &want, lab->cfg->wheel.move_timeout_s, &rb, err);
	if (rc == RIG_OK && lround(rb) != lround(want))
		rc = rig_error_set(err, RIG_ETIMEOUT,
			"wheel: '%s' %s: at slot %ld, asked %ld", c->wheel.device,
			c->wheel.property, lround(rb), lround(want));
	if (rc == RIG_OK)
		lab->wheel.slot = slot;
	return rc;
}

static int indi_wheel_count(struct rig_lab *lab, int *n,
			    struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	double v, lo, hi;
	int rc = ilab_property(lab, c->wheel.device, c->wheel.property,
			  "indi.wheel.property", err);

	if (rc == RIG_OK)
		rc = rig_indi_number(lab->indi, c->wheel.device,
				     c->wheel.property, c->wheel.element, &v,
				     &lo, &hi, NULL);
	if (rc == RIG_EINVAL)
		return rig_error_set(err, rc, "indi: '%s' %s has no element "
				     "%s; check indi.wheel.element",
				     c->wheel.device, c->wheel.property,
				     c->wheel.element);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "wheel: '%s' %s: %s",
				     c->wheel.device, c->wheel.property,
				     rig_status_text(rc));
	*n = (int)lround(hi) - c->wheel.first_slot + 1;
	return RIG_OK;
}

/* ---- switches: lamp, beam block, shutter ---- */

static int indi_line_set(struct rig_lab *lab, enum rig_line which, int on,
			 struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	const struct rig_indi_switch_cfg *s = which == RIG_LINE_LAMP
		? &c->lamp : &c->beam_block;
	int rc;

	lab->lines.state[which] = -1;
	if (which == RIG_LINE_LAMP)
		lab->rb.lamp_cmd = on ? 1 : 0;
	if (which == RIG_LINE_SHUTTER)
		rc = ilab_switch_on(lab, c->camera.device, c->camera.frame_type,
			       on ? c->camera.light : c->camera.dark,
			       "indi.camera.frame_type", err);
	else
		rc = ilab_switch_on(lab, s->device, s->property,
			       on ? s->on : s->off, which == RIG_LINE_LAMP
			       ? "indi.lamp" : "indi.beam_block", err);
	if (rc == RIG_OK)
		lab->lines.state[which] = on ? 1 : 0;
	return rc;
}

/* ---- camera ---- */

/* The window: CCD_FRAME over camera.col0.. by n_cols and the span of
 * camera.rows, so the BLOB holds every row asked and little else. */
static int camera_window(struct rig_lab *lab, struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	const struct rig_camera_cfg *cam = &lab->cfg->camera;
	static const char *const el[4] = { "X", "Y", "WIDTH", "HEIGHT" };
	double v[4], rb;
	int rc = ilab_property(lab, c->camera.device, c->camera.frame,
			  "indi.camera.frame", err), i, same = 1;

	v[0] = cam->col0;
	v[1] = cam->rows[0];
	v[2] = cam->n_cols;
	v[3] = cam->rows[cam->n_rows - 1] - cam->rows[0] + 1;
	/* Set only when the driver's differs (a reconnected or restarted
	 * driver is back at its full chip). */
	for (i = 0; rc == RIG_OK && i < 4; i++)
		same &= rig_indi_number(lab->indi, c->camera.device,
			c->camera.frame, el[i], &rb, NULL, NULL, NULL) ==
			RIG_OK && fabs(rb - v[i]) < 0.5;
	if (rc == RIG_OK && same && !lab->indi_cam_fresh)
		return RIG_OK;
	if (rc == RIG_OK)
		rc = ilab_numbers(lab, c->camera.device, c->camera.frame, 4, el, v,
			     c->timeout_s, &rb, err);
	/* Read back: a driver still connecting may answer with its full
	 * chip; the next capture then sends the window again. */
	for (i = 0, same = 1; rc == RIG_OK && i < 4; i++)
		same &= rig_indi_number(lab->indi, c->camera.device,
			c->camera.frame, el[i], &rb, NULL, NULL, NULL) ==
			RIG_OK && fabs(rb - v[i]) < 0.5;
	if (rc == RIG_OK)
		lab->indi_cam_fresh = !same;
	return rc;
}

static int indi_open(struct rig_lab *lab, int dev, struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	int i, rc;

	switch (dev) {
	case RIG_DEV_STAGE:
		lab->stage.homed = 0;
		return ilab_property(lab, c->stage.device, c->stage.property,
				"indi.stage.property", err);
	case RIG_DEV_WHEEL:
		lab->wheel.slot = -1;
		return ilab_property(lab, c->wheel.device, c->wheel.property,
				"indi.wheel.property", err);
	case RIG_DEV_CAMERA:
		lab->indi_cam_fresh = 1;
		rc = ilab_property(lab, c->camera.device, c->camera.exposure,
			      "indi.camera.exposure", err);
		if (rc == RIG_OK)
			rc = ilab_property(lab, c->camera.device, c->camera.blob,
				      "indi.camera.blob", err);
		return rc == RIG_OK ? camera_window(lab, err) : rc;
	case RIG_DEV_GPIO:
		for (i = 0; i < RIG_LINE_COUNT; i++)
			lab->lines.state[i] = -1;
		rc = ilab_device(lab, c->lamp.device, err);
		if (rc == RIG_OK)
			rc = ilab_device(lab, c->beam_block.device, err);
		return rc == RIG_OK ? ilab_device(lab, c->camera.device, err) : rc;
	default:
		return rig_error_set(err, RIG_EINVAL, "monitor: not on the "
				     "indi backend; set monitor.enabled false");
	}
}

static void indi_close(struct rig_lab *lab, int dev)
{
	int i;

	/* The devices stay connected on the server; what we knew of them
	 * is forgotten, so the next use reads it again. */
	if (dev == RIG_DEV_GPIO)
		for (i = 0; i < RIG_LINE_COUNT; i++)
			lab->lines.state[i] = -1;
	if (dev == RIG_DEV_WHEEL)
		lab->wheel.slot = -1;
	if (dev == RIG_DEV_STAGE)
		lab->stage.homed = 0;
}

/* What the frame was taken under, read back after it: slot and lamp. */
static void frame_readback(struct rig_lab *lab)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	double v = -1;
	int on = -1;

	lab->rb.filter_cmd = lab->wheel.slot < 0 ? -1
			     : lab->wheel.slot + c->wheel.first_slot;
	if (rig_indi_number(lab->indi, c->wheel.device, c->wheel.property,
			    c->wheel.element, &v, NULL, NULL, NULL) != RIG_OK)
		v = -1;
	lab->rb.filter_rb = (int)lround(v);
	if (rig_indi_switch(lab->indi, c->lamp.device, c->lamp.property,
			    c->lamp.on, &on, NULL) != RIG_OK)
		on = -1;
	lab->rb.lamp_rb = on;
	lab->rb.valid = 1;
}

/* Expose and wait for the BLOB; the exposure's property deleted or the
 * device disconnected on the way is RIG_EDISCONNECT. */
static int expose(struct rig_lab *lab, double t, unsigned char **data,
		  size_t *len, struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	const char *dev = c->camera.device;
	const char *el[1] = { c->camera.exposure_element };
	double t_end = rig_hal_now(lab->hal) + t + c->timeout_s;
	struct rig_indi_prop p0, p;
	unsigned long g0 = 0, gen = rig_indi_gen(lab->indi);
	int rc = rig_indi_prop(lab->indi, dev, c->camera.exposure, &p0), on;

	rig_indi_blob(lab->indi, dev, c->camera.blob, ~0UL, data, len, &g0);
	if (rc == RIG_OK)
		rc = rig_indi_send_numbers(lab->indi, dev, c->camera.exposure,
					   1, el, &t);
	while (rc == RIG_OK) {
		rc = rig_indi_blob(lab->indi, dev, c->camera.blob, g0, data,
				   len, NULL);
		if (rc != RIG_EAGAIN)
			break;
		rc = rig_indi_prop(lab->indi, dev, c->camera.exposure, &p);
		if (rc == RIG_OK && (!p.defined ||
		    rig_indi_switch(lab->indi, dev, "CONNECTION", "CONNECT",
				    &on, NULL) != RIG_OK || !on))
			return rig_error_set(err, RIG_EDISCONNECT,
				"camera: '%s' %s: disconnected during a %g s "
				"exposure", dev, c->camera.exposure, t);
		if (rc == RIG_OK && p.gen > p0.gen &&
		    p.state == RIG_INDI_ALERT) {
			char said[160];

			rig_indi_message(lab->indi, dev, said, sizeof(said));
			return rig_error_set(err, RIG_EDEVICE,
				"camera: '%s' %s: a %g s exposure failed "
				"(Alert)%s%s", dev, c->camera.exposure, t,
				said[0] ? "; it said: " : "", said);
		}
		if (rc == RIG_OK)
			rc = ilab_wait(lab, &gen, t_end, dev,
					 c->camera.exposure, err);
	}
	if (rc == RIG_ETIMEOUT)
		return rig_error_set(err, rc, "camera: '%s' %s: no image "
			"within %.1f s of a %g s exposure", dev, c->camera.blob,
			c->timeout_s, t);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "camera: '%s' %s: %s", dev,
				     c->camera.exposure, rig_status_text(rc));
	return RIG_OK;
}

static int indi_capture(struct rig_lab *lab, double t, struct rig_image *img,
			struct rig_error *err)
{
	const struct rig_indi_cfg *c = ICFG(lab);
	int shut = lab->lines.state[RIG_LINE_SHUTTER] == 1;
	unsigned char *data = NULL;
	double t_rb = -1, bits;
	size_t len = 0;
	int rc, attempt;

	lab->rb.valid = 0;
	if (!(t > 0 && t < 4000))
		return rig_error_set(err, RIG_EINVAL,
				     "camera: exposure %g s out of range", t);
	rc = ilab_property(lab, c->camera.device, c->camera.exposure,
		      "indi.camera.exposure", err);
	/* A frame of the wrong size right after a reconnect is the driver
	 * resetting its window behind ours: once, the window again. */
	for (attempt = 0; rc == RIG_OK && attempt < 2; attempt++) {
		struct rig_error e1;

		rig_error_clear(&e1);
		rc = camera_window(lab, &e1);
		/* The shutter as commanded, again: a driver restarted
		 * since has forgotten it (an unknown shutter is closed). */
		if (rc == RIG_OK)
			rc = ilab_switch_on(lab, c->camera.device,
				       c->camera.frame_type, shut
				       ? c->camera.light : c->camera.dark,
				       "indi.camera.frame_type", &e1);
		if (rc == RIG_OK)
			rc = expose(lab, t, &data, &len, &e1);
		if (rc == RIG_OK)
			rc = rig_indi_fits_image(data, len, &lab->cfg->camera,
						 c->camera.device, img, &t_rb,
						 &e1);
		free(data);
		data = NULL;
		if (rc == RIG_EPROTO && attempt == 0) {
			lab->indi_cam_fresh = 1;
			rc = RIG_OK;
			continue;
		}
		if (rc != RIG_OK)
			return rig_error_set(err, rc, "%s", e1.msg);
		break;
	}
	if (rc != RIG_OK)
		return rc;
	if (!(fabs(t_rb - t) <= 1e-3 * t + 1e-6))
		return rig_error_set(err, RIG_EPROTO,
			"camera: '%s': the frame's EXPTIME is %g s, asked %g s",
			c->camera.device, t_rb, t);
	if (rig_indi_number(lab->indi, c->camera.device, "CCD_INFO",
			    "CCD_BITSPERPIXEL", &bits, NULL, NULL,
			    NULL) == RIG_OK && bits >= 1 && bits <= 16)
		img->bits = (int)bits;
	img->t_exp_s = t;
	img->seq = ++lab->camera.seq;
	frame_readback(lab);
	lab->rb.exptime_s = t_rb;
	return RIG_OK;
}

static int indi_monitor(struct rig_lab *lab, double *level,
			struct rig_error *err)
{
	(void)lab;
	(void)level;
	return rig_error_set(err, RIG_EINVAL, "monitor: not on the indi "
			     "backend; set monitor.enabled false");
}

const struct rig_lab_ops rig_lab_indi_ops = {
	indi_open, indi_close, indi_home, indi_move, indi_stop,
	indi_wheel_goto, indi_wheel_count, indi_line_set, indi_capture,
	indi_monitor,
};
