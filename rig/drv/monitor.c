/*
 * monitor.c - the lamp monitor photodiode over HID (monitor_report.h):
 * one READ per frame, so every frame carries the lamp level it was taken
 * under (FITS MONITOR) and the reduction can divide out source drift.
 */
#include <string.h>

#include "rig/devices.h"
#include "rig/monitor_report.h"

#define MONITOR_TIMEOUT_MS 200
#define MONITOR_TRIES 3

int rig_monitor_open(struct rig_monitor *m, const struct rig_hal *hal,
		     const struct rig_monitor_cfg *cfg, struct rig_error *err)
{
	int rc;

	memset(m, 0, sizeof(*m));
	m->cfg = cfg;
	rc = rig_hal_hid_open(hal, cfg->vid, cfg->pid,
			      cfg->serial[0] ? cfg->serial : NULL, &m->hid);
	if (rc != RIG_OK)
		return rig_error_set(err, rc,
				     "monitor: hid %04x:%04x: cannot open: %s",
				     cfg->vid, cfg->pid, rig_status_text(rc));
	return RIG_OK;
}

/* One READ round trip; RIG_ETIMEOUT when no matching report came. */
static int read_once(struct rig_monitor *m, struct rig_monitor_in *in,
		     struct rig_error *err)
{
	uint8_t buf[RIG_MONITOR_REPORT_LEN];
	size_t got;
	int rc;

	rig_monitor_out_encode(++m->seq, buf);
	rc = rig_hal_hid_write(&m->hid, buf, sizeof(buf));
	if (rc == RIG_OK)
		rc = rig_hal_hid_read(&m->hid, buf, sizeof(buf), &got,
				      MONITOR_TIMEOUT_MS);
	if (rc == RIG_ETIMEOUT)
		return rc;
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "monitor: %s",
				     rig_status_text(rc));
	if (rig_monitor_in_decode(buf, got, in) != RIG_OK)
		return rig_error_set(err, RIG_EPROTO,
				     "monitor: malformed input report");
	return in->seq == m->seq ? RIG_OK : RIG_ETIMEOUT;
}

int rig_monitor_read(struct rig_monitor *m, double *level,
		     struct rig_error *err)
{
	struct rig_monitor_in in;
	int i, rc = RIG_ETIMEOUT;

	for (i = 0; i < MONITOR_TRIES && rc == RIG_ETIMEOUT; i++)
		rc = read_once(m, &in, err);
	if (rc == RIG_ETIMEOUT)
		return rig_error_set(err, rc, "monitor: no reading in %d tries",
				     MONITOR_TRIES);
	if (rc != RIG_OK)
		return rc;
	if (in.flags & RIG_MONITOR_OVERRANGE)
		return rig_error_set(err, RIG_EDEVICE,
				     "monitor: photocurrent over range");
	*level = in.current_pa / m->cfg->nominal_pa;
	return RIG_OK;
}

void rig_monitor_close(struct rig_monitor *m)
{
	rig_hal_hid_close(&m->hid);
}
