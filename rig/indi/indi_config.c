/*
 * indi_config.c - the config's "indi" section (indi.h, docs/rig-config.md):
 * where the indiserver is and which device and property is each part of
 * the lab.  The defaults name INDI's standard properties and the
 * simulators of `indi-bin` (scripts/rig-indi.sh), so a lab writes only
 * its device names.
 */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "rig/config.h"
#include "rig/config_json.h"

#define S(s, k) { #k, K_STR, offsetof(s, k), 0, RIG_INDI_NAME_MAX - 1 }

static void sw(struct rig_indi_switch_cfg *s, const char *dev,
	       const char *prop, const char *on, const char *off)
{
	snprintf(s->device, sizeof(s->device), "%s", dev);
	snprintf(s->property, sizeof(s->property), "%s", prop);
	snprintf(s->on, sizeof(s->on), "%s", on);
	snprintf(s->off, sizeof(s->off), "%s", off);
}

void rig_indi_cfg_defaults(struct rig_indi_cfg *c)
{
	memset(c, 0, sizeof(*c));
	strcpy(c->host, "localhost");
	c->port = 7624;			/* INDI's registered port */
	c->connect_timeout_s = 5;
	c->timeout_s = 10;
	strcpy(c->camera.device, "CCD Simulator");
	strcpy(c->camera.exposure, "CCD_EXPOSURE");
	strcpy(c->camera.exposure_element, "CCD_EXPOSURE_VALUE");
	strcpy(c->camera.blob, "CCD1");
	strcpy(c->camera.frame, "CCD_FRAME");
	strcpy(c->camera.frame_type, "CCD_FRAME_TYPE");
	strcpy(c->camera.light, "FRAME_LIGHT");
	strcpy(c->camera.dark, "FRAME_DARK");
	strcpy(c->wheel.device, "Filter Simulator");
	strcpy(c->wheel.property, "FILTER_SLOT");
	strcpy(c->wheel.element, "FILTER_SLOT_VALUE");
	c->wheel.first_slot = 1;	/* INDI counts filter slots from 1 */
	strcpy(c->stage.device, "Rotator Simulator");
	strcpy(c->stage.property, "ABS_ROTATOR_ANGLE");
	strcpy(c->stage.element, "ANGLE");
	strcpy(c->stage.abort, "ROTATOR_ABORT_MOTION");
	strcpy(c->stage.abort_element, "ABORT");
	c->stage.wrap360 = 1;		/* INDI rotators take 0..360 deg */
	sw(&c->lamp, "Light Panel Simulator", "FLAT_LIGHT_CONTROL",
	   "FLAT_LIGHT_ON", "FLAT_LIGHT_OFF");
	sw(&c->beam_block, "Beam Block", "FLAT_LIGHT_CONTROL",
	   "FLAT_LIGHT_ON", "FLAT_LIGHT_OFF");
}

static const struct rig_cfg_field top_fields[] = {
	S(struct rig_indi_cfg, host),
	{ "port", K_INT, offsetof(struct rig_indi_cfg, port), 1, 65535 },
	NUM(struct rig_indi_cfg, connect_timeout_s, 0.1, 60),
	NUM(struct rig_indi_cfg, timeout_s, 0.1, 600),
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field camera_fields[] = {
	{ "device", K_STR, offsetof(struct rig_indi_cfg, camera.device), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "exposure", K_STR, offsetof(struct rig_indi_cfg, camera.exposure),
	  0, RIG_INDI_NAME_MAX - 1 },
	{ "exposure_element", K_STR, offsetof(struct rig_indi_cfg,
	  camera.exposure_element), 0, RIG_INDI_NAME_MAX - 1 },
	{ "blob", K_STR, offsetof(struct rig_indi_cfg, camera.blob), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "frame", K_STR, offsetof(struct rig_indi_cfg, camera.frame), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "frame_type", K_STR, offsetof(struct rig_indi_cfg,
	  camera.frame_type), 0, RIG_INDI_NAME_MAX - 1 },
	{ "light", K_STR, offsetof(struct rig_indi_cfg, camera.light), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "dark", K_STR, offsetof(struct rig_indi_cfg, camera.dark), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field wheel_fields[] = {
	{ "device", K_STR, offsetof(struct rig_indi_cfg, wheel.device), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "property", K_STR, offsetof(struct rig_indi_cfg, wheel.property),
	  0, RIG_INDI_NAME_MAX - 1 },
	{ "element", K_STR, offsetof(struct rig_indi_cfg, wheel.element), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "first_slot", K_INT, offsetof(struct rig_indi_cfg,
	  wheel.first_slot), 0, 1 },
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field stage_fields[] = {
	{ "device", K_STR, offsetof(struct rig_indi_cfg, stage.device), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "property", K_STR, offsetof(struct rig_indi_cfg, stage.property),
	  0, RIG_INDI_NAME_MAX - 1 },
	{ "element", K_STR, offsetof(struct rig_indi_cfg, stage.element), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "abort", K_STR, offsetof(struct rig_indi_cfg, stage.abort), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "abort_element", K_STR, offsetof(struct rig_indi_cfg,
	  stage.abort_element), 0, RIG_INDI_NAME_MAX - 1 },
	{ "wrap360", K_BOOL, offsetof(struct rig_indi_cfg, stage.wrap360),
	  0, 1 },
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field switch_fields[] = {
	{ "device", K_STR, offsetof(struct rig_indi_switch_cfg, device), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "property", K_STR, offsetof(struct rig_indi_switch_cfg, property),
	  0, RIG_INDI_NAME_MAX - 1 },
	{ "on", K_STR, offsetof(struct rig_indi_switch_cfg, on), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ "off", K_STR, offsetof(struct rig_indi_switch_cfg, off), 0,
	  RIG_INDI_NAME_MAX - 1 },
	{ NULL, 0, 0, 0, 0 }
};

/* Every name must be given: an empty one would address nothing. */
static int check_names(const struct rig_indi_cfg *c, const char *name,
		       struct rig_error *err)
{
	static const struct { const char *sec, *key; size_t off; } need[] = {
#define N(sec, key, f) { sec, key, offsetof(struct rig_indi_cfg, f) }
		N("indi", "host", host),
		N("indi.camera", "device", camera.device),
		N("indi.camera", "exposure", camera.exposure),
		N("indi.camera", "exposure_element", camera.exposure_element),
		N("indi.camera", "blob", camera.blob),
		N("indi.camera", "frame", camera.frame),
		N("indi.camera", "frame_type", camera.frame_type),
		N("indi.camera", "light", camera.light),
		N("indi.camera", "dark", camera.dark),
		N("indi.wheel", "device", wheel.device),
		N("indi.wheel", "property", wheel.property),
		N("indi.wheel", "element", wheel.element),
		N("indi.stage", "device", stage.device),
		N("indi.stage", "property", stage.property),
		N("indi.stage", "element", stage.element),
		N("indi.stage", "abort", stage.abort),
		N("indi.stage", "abort_element", stage.abort_element),
		N("indi.lamp", "device", lamp.device),
		N("indi.lamp", "property", lamp.property),
		N("indi.lamp", "on", lamp.on),
		N("indi.lamp", "off", lamp.off),
		N("indi.beam_block", "device", beam_block.device),
		N("indi.beam_block", "property", beam_block.property),
		N("indi.beam_block", "on", beam_block.on),
		N("indi.beam_block", "off", beam_block.off),
#undef N
	};
	size_t i;

	for (i = 0; i < sizeof(need) / sizeof(need[0]); i++)
		if (!((const char *)c + need[i].off)[0])
			return rig_cfg_bad(err, name, need[i].sec, need[i].key,
					   "empty; name the INDI device, "
					   "property or element");
	return RIG_OK;
}

int rig_indi_config_parse(struct rig_indi_cfg *c, const cJSON *o,
			  const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "camera", "wheel", "stage",
					     "lamp", "beam_block", NULL };
	int rc = rig_cfg_apply(c, top_fields, o, extra, name, "indi", err);

#define SEC(k) cJSON_GetObjectItemCaseSensitive(o, k)
	if (rc == RIG_OK && o)
		rc = rig_cfg_apply(c, camera_fields, SEC("camera"), NULL, name,
				   "indi.camera", err);
	if (rc == RIG_OK && o)
		rc = rig_cfg_apply(c, wheel_fields, SEC("wheel"), NULL, name,
				   "indi.wheel", err);
	if (rc == RIG_OK && o)
		rc = rig_cfg_apply(c, stage_fields, SEC("stage"), NULL, name,
				   "indi.stage", err);
	if (rc == RIG_OK && o)
		rc = rig_cfg_apply(&c->lamp, switch_fields, SEC("lamp"), NULL,
				   name, "indi.lamp", err);
	if (rc == RIG_OK && o)
		rc = rig_cfg_apply(&c->beam_block, switch_fields,
				   SEC("beam_block"), NULL, name,
				   "indi.beam_block", err);
#undef SEC
	return rc == RIG_OK ? check_names(c, name, err) : rc;
}
