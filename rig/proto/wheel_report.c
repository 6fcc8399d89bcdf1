/*
 * wheel_report.c - encode and check the ND wheel's HID reports.
 */
#include <string.h>

#include "rig/status.h"
#include "rig/wheel_report.h"

void rig_wheel_out_encode(const struct rig_wheel_out *o,
			  uint8_t buf[RIG_WHEEL_REPORT_LEN])
{
	memset(buf, 0, RIG_WHEEL_REPORT_LEN);
	buf[0] = RIG_WHEEL_OUT_ID;
	buf[1] = o->cmd;
	buf[2] = o->slot;
	buf[3] = o->seq;
}

int rig_wheel_out_decode(const uint8_t *buf, size_t len,
			 struct rig_wheel_out *o)
{
	if (len != RIG_WHEEL_REPORT_LEN || buf[0] != RIG_WHEEL_OUT_ID ||
	    buf[1] < RIG_WHEEL_GOTO || buf[1] > RIG_WHEEL_HOME)
		return RIG_EPROTO;
	o->cmd = buf[1];
	o->slot = buf[2];
	o->seq = buf[3];
	return RIG_OK;
}

void rig_wheel_in_encode(const struct rig_wheel_in *in,
			 uint8_t buf[RIG_WHEEL_REPORT_LEN])
{
	memset(buf, 0, RIG_WHEEL_REPORT_LEN);
	buf[0] = RIG_WHEEL_IN_ID;
	buf[1] = in->flags;
	buf[2] = in->slot;
	buf[3] = in->seq;
	buf[4] = in->n_slots;
	buf[5] = in->fault;
}

int rig_wheel_in_decode(const uint8_t *buf, size_t len,
			struct rig_wheel_in *in)
{
	if (len != RIG_WHEEL_REPORT_LEN || buf[0] != RIG_WHEEL_IN_ID)
		return RIG_EPROTO;
	in->flags = buf[1];
	in->slot = buf[2];
	in->seq = buf[3];
	in->n_slots = buf[4];
	in->fault = buf[5];
	if (in->n_slots == 0 || in->n_slots > RIG_WHEEL_SLOTS_MAX ||
	    (in->slot != RIG_WHEEL_SLOT_UNKNOWN && in->slot >= in->n_slots) ||
	    (in->flags & ~(RIG_WHEEL_MOVING | RIG_WHEEL_HOMED | RIG_WHEEL_FAULT)))
		return RIG_EPROTO;
	return RIG_OK;
}
