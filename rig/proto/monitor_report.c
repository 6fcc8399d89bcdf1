/*
 * monitor_report.c - encode and check the monitor photodiode's reports.
 */
#include <string.h>

#include "rig/bytes.h"
#include "rig/monitor_report.h"
#include "rig/status.h"

void rig_monitor_out_encode(uint8_t seq, uint8_t buf[RIG_MONITOR_REPORT_LEN])
{
	memset(buf, 0, RIG_MONITOR_REPORT_LEN);
	buf[0] = RIG_MONITOR_OUT_ID;
	buf[1] = RIG_MONITOR_READ;
	buf[2] = seq;
}

int rig_monitor_out_decode(const uint8_t *buf, size_t len, uint8_t *seq)
{
	if (len != RIG_MONITOR_REPORT_LEN || buf[0] != RIG_MONITOR_OUT_ID ||
	    buf[1] != RIG_MONITOR_READ)
		return RIG_EPROTO;
	*seq = buf[2];
	return RIG_OK;
}

void rig_monitor_in_encode(const struct rig_monitor_in *in,
			   uint8_t buf[RIG_MONITOR_REPORT_LEN])
{
	memset(buf, 0, RIG_MONITOR_REPORT_LEN);
	buf[0] = RIG_MONITOR_IN_ID;
	buf[1] = in->seq;
	rig_put_u32(buf + 2, in->current_pa);
	buf[6] = in->flags;
}

int rig_monitor_in_decode(const uint8_t *buf, size_t len,
			  struct rig_monitor_in *in)
{
	if (len != RIG_MONITOR_REPORT_LEN || buf[0] != RIG_MONITOR_IN_ID ||
	    (buf[6] & ~RIG_MONITOR_OVERRANGE) || buf[7] != 0)
		return RIG_EPROTO;
	in->seq = buf[1];
	in->current_pa = rig_get_u32(buf + 2);
	in->flags = buf[6];
	return RIG_OK;
}
