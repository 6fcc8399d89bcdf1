/*
 * sim_wheel.c - device side of the HID ND wheel (wheel_report.h): moves
 * 0.3 s per slot on the virtual clock and answers each QUERY with one
 * input report.
 */
#include <stdlib.h>
#include <string.h>

#include "rig/sim_devices.h"
#include "rig/status.h"
#include "rig/wheel_report.h"

#define SLOT_TIME_S 0.3

static void update(struct sim_wheel *w, const struct rig_sim_core *core)
{
	if (w->slot != w->target && !w->stalled && core->t_s >= w->t_done)
		w->slot = w->target;
}

int rig_sim_wheel_write(struct sim_wheel *w, struct rig_sim_core *core,
			const uint8_t *buf, size_t len)
{
	struct rig_wheel_out o;
	struct rig_wheel_in in;
	int kind;

	if (rig_wheel_out_decode(buf, len, &o) != RIG_OK)
		return RIG_OK;	/* a HID device drops bad reports */
	update(w, core);
	if (o.cmd == RIG_WHEEL_GOTO && o.slot < core->cfg->wheel.n_slots) {
		kind = rig_sim_core_event(core, RIG_DEV_WHEEL, NULL);
		if (core->gone[RIG_DEV_WHEEL])
			return RIG_EDISCONNECT;
		w->stalled = kind == RIG_FAULT_STALL;
		w->t_done = core->t_s + SLOT_TIME_S * abs(o.slot - w->slot);
		w->target = o.slot;
	}
	if (o.cmd == RIG_WHEEL_HOME) {
		w->target = 0;
		w->t_done = core->t_s + SLOT_TIME_S * w->slot;
	}
	in.flags = RIG_WHEEL_HOMED;
	if (w->slot != w->target)
		in.flags |= RIG_WHEEL_MOVING;
	in.slot = (uint8_t)w->slot;
	in.seq = o.seq;
	in.n_slots = (uint8_t)(core->cfg->sim.wheel_slots > 0
			       ? core->cfg->sim.wheel_slots
			       : core->cfg->wheel.n_slots);
	in.fault = 0;
	if (o.cmd == RIG_WHEEL_QUERY) {
		rig_wheel_in_encode(&in, w->report);
		w->have_report = 1;
	}
	return RIG_OK;
}

int rig_sim_wheel_read(struct sim_wheel *w, struct rig_sim_core *core,
		       uint8_t *buf, size_t cap, size_t *got,
		       unsigned timeout_ms)
{

	if (!w->have_report || cap < RIG_WHEEL_REPORT_LEN) {
		core->t_s += timeout_ms * 1e-3;
		return RIG_ETIMEOUT;
	}
	memcpy(buf, w->report, RIG_WHEEL_REPORT_LEN);
	*got = RIG_WHEEL_REPORT_LEN;
	w->have_report = 0;
	return RIG_OK;
}

void rig_sim_wheel_reset(struct sim_wheel *w)
{
	w->have_report = 0;
}

double rig_sim_wheel_trans(const struct sim_wheel *w,
			   const struct rig_sim_core *core)
{
	return core->cfg->wheel.trans[w->slot];
}
