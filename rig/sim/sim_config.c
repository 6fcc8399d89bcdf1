/*
 * sim_config.c - the simulator's configuration (sim_config.h): the
 * virtual lab's defaults and the "vlab" and "sim" sections of the config
 * file, parsed with the shared section tables (config_json.h).
 */
#include <cJSON.h>
#include <stddef.h>
#include <string.h>

#include "rig/config_json.h"
#include "rig/devices.h"
#include "rig/sim_config.h"

static const struct rig_cfg_field vlab_fields[] = {
	NUM(struct rig_vlab_cfg, lamp_rate_dn_s, 0, 1e12),
	NUM(struct rig_vlab_cfg, lamp_drift_per_h, -1, 1),
	NUM(struct rig_vlab_cfg, lens_scale_deg, 1e-3, 1e3),
	NUM(struct rig_vlab_cfg, lens_floor, 0, 1),
	NUM(struct rig_vlab_cfg, gradient, -1, 1),
	NUM(struct rig_vlab_cfg, ambient_dn_s, 0, 1e9),
	NUM(struct rig_vlab_cfg, atmos_frac, 0, 1),
	NUM(struct rig_vlab_cfg, dark_dn_s, 0, 1e9),
	NUM(struct rig_vlab_cfg, read_noise_dn, 0, 1e4),
	NUM(struct rig_vlab_cfg, gain_e_per_dn, 1e-3, 1e3),
	NUM(struct rig_vlab_cfg, hot_frac, 0, 1),
	NUM(struct rig_vlab_cfg, hot_dn_s, 0, 1e9),
	INT(struct rig_vlab_cfg, sat_dn, 1, 65535),
	{ NULL, 0, 0, 0, 0 }
};

static const struct rig_cfg_field ghost_fields[] = {
	NUM(struct rig_ghost, amp, 0, 10),
	NUM(struct rig_ghost, col_at0, -1e5, 1e5),
	NUM(struct rig_ghost, px_per_deg, -1e4, 1e4),
	NUM(struct rig_ghost, sigma_px, 1e-3, 1e5),
	NUM(struct rig_ghost, theta_c_deg, -360, 360),
	NUM(struct rig_ghost, theta_w_deg, 1e-3, 1e3),
	{ NULL, 0, 0, 0, 0 }
};

static int parse_vlab(struct rig_vlab_cfg *vl, const cJSON *o,
		      const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "bias_dn", "ghosts", "seed",
					     NULL };
	const cJSON *b = cJSON_GetObjectItemCaseSensitive(o, "bias_dn");
	const cJSON *g = cJSON_GetObjectItemCaseSensitive(o, "ghosts");
	const cJSON *s = cJSON_GetObjectItemCaseSensitive(o, "seed");
	const cJSON *v;
	int rc = rig_cfg_apply(vl, vlab_fields, o, extra, name, "vlab", err);

	if (rc != RIG_OK)
		return rc;
	if (b && rig_cfg_num_array(b, vl->bias_dn, RIG_VLAB_CHANNELS, 0,
				   65535) != RIG_VLAB_CHANNELS)
		return rig_cfg_bad(err, name, "vlab", "bias_dn",
				   "expected 8 channel offsets in DN");
	if (s && !(cJSON_IsNumber(s) && s->valuedouble >= 0))
		return rig_cfg_bad(err, name, "vlab", "seed",
				   "expected an integer");
	if (s)
		vl->seed = (uint64_t)s->valuedouble;
	if (!g)
		return RIG_OK;
	if (!cJSON_IsArray(g) || cJSON_GetArraySize(g) > RIG_VLAB_GHOSTS_MAX)
		return rig_cfg_bad(err, name, "vlab", "ghosts",
				   "expected a list of at most 4 ghosts");
	vl->n_ghosts = 0;
	cJSON_ArrayForEach(v, g) {
		struct rig_ghost *gh = &vl->ghost[vl->n_ghosts++];

		rc = rig_cfg_apply(gh, ghost_fields, v, NULL, name,
				   "vlab.ghosts", err);
		if (rc != RIG_OK)
			return rc;
	}
	return RIG_OK;
}

int rig_sim_fault_parse(const void *json, struct rig_fault *f,
			const char *name, struct rig_error *err)
{
	static const char *const kinds[] = { "timeout", "disconnect", "stall",
					     "crc", "miss", "kill" };
	static const struct rig_cfg_field tab[] = {
		{ "at", K_INT, offsetof(struct rig_fault, at), 1, 1e9 },
		{ "count", K_INT, offsetof(struct rig_fault, count), 1, 1e9 },
		NUM(struct rig_fault, value, -360, 360),
		{ NULL, 0, 0, 0, 0 }
	};
	static const char *const extra[] = { "device", "kind", NULL };
	const cJSON *o = json;
	int rc;

	memset(f, 0, sizeof(*f));
	f->at = 1;
	f->count = 1;
	f->value = 0.5;
	rc = rig_cfg_apply(f, tab, o, extra, name, "sim.faults", err);
	if (rc != RIG_OK)
		return rc;
	f->device = rig_cfg_lookup(rig_device_names, RIG_DEV_COUNT,
		cJSON_GetStringValue(
			cJSON_GetObjectItemCaseSensitive(o, "device")));
	f->kind = rig_cfg_lookup(kinds, RIG_FAULT_KIND_COUNT,
		cJSON_GetStringValue(
			cJSON_GetObjectItemCaseSensitive(o, "kind")));
	if (f->device < 0)
		return rig_cfg_bad(err, name, "sim.faults", "device",
			"expected stage, wheel, camera, monitor or gpio");
	if (f->kind < 0)
		return rig_cfg_bad(err, name, "sim.faults", "kind",
			"expected timeout, disconnect, stall, crc, miss "
			"or kill");
	return RIG_OK;
}

static int parse_sim(struct rig_sim_config *sc, const cJSON *o,
		     const char *name, struct rig_error *err)
{
	static const char *const extra[] = { "faults", NULL };
	static const struct rig_cfg_field tab[] = {
		{ "real_delay_s", K_NUM,
		  offsetof(struct rig_sim_config, real_delay_s), 0, 10 },
		{ "monitor_noise", K_NUM,
		  offsetof(struct rig_sim_config, monitor_noise), 0, 0.1 },
		{ "stage_error_deg", K_NUM,
		  offsetof(struct rig_sim_config, stage_error_deg), 0, 1 },
		{ "wheel_slots", K_INT,
		  offsetof(struct rig_sim_config, wheel_slots), 0, 12 },
		{ NULL, 0, 0, 0, 0 }
	};
	const cJSON *fl = cJSON_GetObjectItemCaseSensitive(o, "faults");
	const cJSON *v;
	int rc = rig_cfg_apply(sc, tab, o, extra, name, "sim", err);

	if (rc != RIG_OK || !fl)
		return rc;
	if (!cJSON_IsArray(fl) || cJSON_GetArraySize(fl) > RIG_FAULTS_MAX)
		return rig_cfg_bad(err, name, "sim", "faults",
				   "expected a list of at most 16 faults");
	sc->n_faults = 0;
	cJSON_ArrayForEach(v, fl) {
		rc = rig_sim_fault_parse(v, &sc->faults[sc->n_faults++], name,
				      err);
		if (rc != RIG_OK)
			return rc;
	}
	return RIG_OK;
}

void rig_sim_config_defaults(struct rig_sim_config *sc)
{
	memset(sc, 0, sizeof(*sc));
	rig_vlab_defaults(&sc->vlab);
	sc->monitor_noise = 5e-4;
}

int rig_sim_config_parse(struct rig_sim_config *sc, const void *vlab,
			 const void *sim, const char *name,
			 struct rig_error *err)
{
	int rc = parse_vlab(&sc->vlab, vlab, name, err);

	return rc == RIG_OK ? parse_sim(sc, sim, name, err) : rc;
}
