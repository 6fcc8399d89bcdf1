/*
 * readback.c - what a frame's header says was read back beside what was
 * commanded (sweep.h): the stage's angle always, and on an INDI lab the
 * filter slot, the exposure the camera wrote and the lamp's switch, so a
 * frame taken by a device that did something else shows it.
 */
#include <math.h>
#include <string.h>

#include "rig/sweep.h"

static void key_long(struct stray_sweep_key *k, const char *key, long v,
		     const char *comment)
{
	memset(k, 0, sizeof(*k));
	k->key = key;
	k->kind = STRAY_SWEEP_KEY_LONG;
	k->l = v;
	k->comment = comment;
}

size_t rig_sweep_readback_keys(const struct rig_lab *lab,
			       struct stray_sweep_key k[RIG_SWEEP_RB_KEYS])
{
	size_t n = 0;

	if (isfinite(lab->theta_rb_deg)) {
		memset(&k[n], 0, sizeof(k[n]));
		k[n].key = STRAY_SWEEP_KEY_ANGLERB;
		k[n].kind = STRAY_SWEEP_KEY_DOUBLE;
		k[n].d = lab->theta_rb_deg;
		k[n++].comment = "[deg] stage read-back angle";
	}
	if (!lab->rb.valid)
		return n;
	key_long(&k[n++], "FILTER", lab->rb.filter_cmd,
		 "filter slot commanded (device numbering)");
	key_long(&k[n++], "FILTERRB", lab->rb.filter_rb,
		 "filter slot read back, -1 unknown");
	memset(&k[n], 0, sizeof(k[n]));
	k[n].key = "EXPTIMRB";
	k[n].kind = STRAY_SWEEP_KEY_DOUBLE;
	k[n].d = lab->rb.exptime_s;
	k[n++].comment = "[s] exposure the camera wrote";
	key_long(&k[n++], "LAMP", lab->rb.lamp_cmd, "lamp commanded, 1 on");
	key_long(&k[n++], "LAMPRB", lab->rb.lamp_rb,
		 "lamp switch read back, 1 on, -1 unknown");
	return n;
}
