/*
 * probe_indi.c - `stray rig probe` for a lab on INDI ("backend": "indi"):
 * the server and every device the config names, through the daemon's own
 * INDI lab (rig/indi/), without moving anything:
 *   switches  lamp off, beam block on, shutter closed, each read back
 *   stage     its angle read (ABS_ROTATOR_ANGLE or the configured one)
 *   wheel     its slot count and the slot it is at
 *   camera    window sent and read back, one 10 ms dark frame
 * A wrong property name fails its device with the config key to fix.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "probe.h"
#include "rig/indi.h"
#include "rig/lab.h"

/* One element of a number property, as the probe reads it. */
static int read_number(struct rig_lab *lab, const char *dev,
		       const char *prop, const char *elem, const char *key,
		       double *v, double *hi, struct rig_error *err)
{
	double lo;
	int rc = rig_indi_number(lab->indi, dev, prop, elem, v, &lo, hi, NULL);

	if (rc == RIG_EINVAL)
		return rig_error_set(err, rc, "indi: '%s' %s has no element "
				     "%s; check %s", dev, prop, elem, key);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "indi: '%s' %s: %s", dev, prop,
				     rig_status_text(rc));
	return RIG_OK;
}

static void probe_switches(struct rig_lab *lab)
{
	const struct rig_indi_cfg *c = &lab->cfg->indi;
	struct rig_error err;
	char what[6 * RIG_INDI_NAME_MAX + 64];
	int rc;

	rig_error_clear(&err);
	rc = lab->ops->open(lab, RIG_DEV_GPIO, &err);
	if (rc == RIG_OK) {
		lab->open_mask |= 1 << RIG_DEV_GPIO;
		rc = lab->ops->line_set(lab, RIG_LINE_LAMP, 0, &err);
	}
	if (rc == RIG_OK)
		rc = lab->ops->line_set(lab, RIG_LINE_BEAM_BLOCK, 1, &err);
	if (rc == RIG_OK)
		rc = lab->ops->line_set(lab, RIG_LINE_SHUTTER, 0, &err);
	snprintf(what, sizeof(what), "lamp '%s' %s off, beam block '%s' %s "
		 "on, shutter '%s' %s, each read back", c->lamp.device,
		 c->lamp.property, c->beam_block.device,
		 c->beam_block.property, c->camera.device, c->camera.dark);
	probe_result("switches", rc, &err, what);
}

static void probe_stage(struct rig_lab *lab)
{
	const struct rig_indi_cfg *c = &lab->cfg->indi;
	struct rig_error err;
	char what[2 * RIG_INDI_NAME_MAX + 64];
	double v = NAN, hi;
	int rc;

	rig_error_clear(&err);
	rc = lab->ops->open(lab, RIG_DEV_STAGE, &err);
	if (rc == RIG_OK) {
		lab->open_mask |= 1 << RIG_DEV_STAGE;
		rc = read_number(lab, c->stage.device, c->stage.property,
				 c->stage.element, "indi.stage.element", &v,
				 &hi, &err);
	}
	snprintf(what, sizeof(what), "'%s' %s at %.3f deg (not moved)",
		 c->stage.device, c->stage.property, v);
	probe_result("stage", rc, &err, what);
}

static void probe_wheel(struct rig_lab *lab)
{
	const struct rig_indi_cfg *c = &lab->cfg->indi;
	struct rig_error err;
	char what[2 * RIG_INDI_NAME_MAX + 64];
	double v = NAN, hi;
	int rc, n = 0;

	rig_error_clear(&err);
	rc = lab->ops->open(lab, RIG_DEV_WHEEL, &err);
	if (rc == RIG_OK) {
		lab->open_mask |= 1 << RIG_DEV_WHEEL;
		rc = lab->ops->wheel_count(lab, &n, &err);
	}
	if (rc == RIG_OK)
		rc = read_number(lab, c->wheel.device, c->wheel.property,
				 c->wheel.element, "indi.wheel.element", &v,
				 &hi, &err);
	if (rc == RIG_OK && n < lab->cfg->wheel.n_slots)
		rc = rig_error_set(&err, RIG_EINVAL, "wheel: '%s' has %d "
				   "slots, the config wheel.n_slots %d",
				   c->wheel.device, n, lab->cfg->wheel.n_slots);
	snprintf(what, sizeof(what), "'%s' %s: %d slots, at INDI slot %.0f "
		 "(not moved)", c->wheel.device, c->wheel.property, n, v);
	probe_result("wheel", rc, &err, what);
}

static void probe_camera(struct rig_lab *lab)
{
	const struct rig_config *cfg = lab->cfg;
	struct rig_image img;
	struct rig_error err;
	char what[2 * RIG_INDI_NAME_MAX + 64];
	int rc;

	rig_error_clear(&err);
	memset(&img, 0, sizeof(img));
	rc = lab->ops->open(lab, RIG_DEV_CAMERA, &err);
	if (rc == RIG_OK) {
		lab->open_mask |= 1 << RIG_DEV_CAMERA;
		img.px = calloc((size_t)cfg->camera.n_rows *
				(size_t)cfg->camera.n_cols, sizeof(*img.px));
		rc = img.px ? lab->ops->capture(lab, 0.01, &img, &err)
			    : rig_error_set(&err, RIG_ENOMEM,
					    "camera: no memory");
	}
	snprintf(what, sizeof(what), "'%s': one 10 ms dark frame, %d x %d "
		 "px, %d-bit", cfg->indi.camera.device, img.n_rows,
		 img.n_cols, img.bits);
	free(img.px);
	probe_result("camera", rc, &err, what);
}

void probe_indi(const struct rig_config *cfg)
{
	struct rig_lab lab;
	struct rig_hal hal;
	int dev;

	memset(&lab, 0, sizeof(lab));
	rig_hal_indi_init(&hal);
	lab.cfg = cfg;
	lab.hal = &hal;
	lab.ops = &rig_lab_indi_ops;
	lab.theta_deg = lab.theta_rb_deg = NAN;
	printf("indi     server %s:%d\n", cfg->indi.host, cfg->indi.port);
	probe_switches(&lab);
	probe_stage(&lab);
	probe_wheel(&lab);
	if (cfg->monitor.enabled)
		printf("monitor  not on the indi backend (monitor.enabled is "
		       "ignored here)\n");
	probe_camera(&lab);
	for (dev = 0; dev < RIG_DEV_COUNT; dev++)
		if (lab.open_mask & (1 << dev))
			lab.ops->close(&lab, dev);
	rig_indi_free(lab.indi);
}
