/*
 * wheel.c - ND filter wheel driver over HID reports (wheel_report.h):
 * GOTO, then QUERY until the wheel reports the slot, not moving, with our
 * sequence number echoed (so a stale report is never mistaken for done).
 */
#include <string.h>

#include "rig/devices.h"

#define WHEEL_POLL_MS 100

int rig_wheel_open(struct rig_wheel *w, const struct rig_hal *hal,
		   const struct rig_wheel_cfg *cfg, struct rig_error *err)
{
	int rc;

	memset(w, 0, sizeof(*w));
	w->cfg = cfg;
	w->hal = hal;
	w->slot = -1;
	rc = rig_hal_hid_open(hal, cfg->vid, cfg->pid,
			      cfg->serial[0] ? cfg->serial : NULL, &w->hid);
	if (rc != RIG_OK)
		return rig_error_set(err, rc,
				     "wheel: hid %04x:%04x: cannot open: %s",
				     cfg->vid, cfg->pid, rig_status_text(rc));
	return RIG_OK;
}

static int send_cmd(struct rig_wheel *w, uint8_t cmd, uint8_t slot,
		    struct rig_error *err)
{
	struct rig_wheel_out o = { cmd, slot, ++w->seq };
	uint8_t buf[RIG_WHEEL_REPORT_LEN];
	int rc;

	rig_wheel_out_encode(&o, buf);
	rc = rig_hal_hid_write(&w->hid, buf, sizeof(buf));
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "wheel: write: %s",
				     rig_status_text(rc));
	return RIG_OK;
}

/* One QUERY round trip; RIG_OK with *in filled. */
static int query(struct rig_wheel *w, struct rig_wheel_in *in,
		 struct rig_error *err)
{
	uint8_t buf[RIG_WHEEL_REPORT_LEN];
	size_t got;
	int rc = send_cmd(w, RIG_WHEEL_QUERY, 0, err);

	if (rc != RIG_OK)
		return rc;
	rc = rig_hal_hid_read(&w->hid, buf, sizeof(buf), &got, WHEEL_POLL_MS);
	if (rc == RIG_ETIMEOUT)
		return rc;
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "wheel: read: %s",
				     rig_status_text(rc));
	if (rig_wheel_in_decode(buf, got, in) != RIG_OK)
		return rig_error_set(err, RIG_EPROTO,
				     "wheel: malformed input report (%zu bytes)",
				     got);
	return RIG_OK;
}

int rig_wheel_goto(struct rig_wheel *w, int slot, struct rig_error *err)
{
	struct rig_wheel_in in;
	double t_end;
	int rc;

	if (slot < 0 || slot >= w->cfg->n_slots)
		return rig_error_set(err, RIG_EINVAL,
				     "wheel: slot %d outside 0..%d", slot,
				     w->cfg->n_slots - 1);
	rc = send_cmd(w, RIG_WHEEL_GOTO, (uint8_t)slot, err);
	if (rc != RIG_OK)
		return rc;
	t_end = rig_hal_now(w->hal) + w->cfg->move_timeout_s;
	while (rig_hal_now(w->hal) <= t_end) {
		rc = query(w, &in, err);
		if (rc == RIG_ETIMEOUT)
			continue;
		if (rc != RIG_OK)
			return rc;
		if (in.flags & RIG_WHEEL_FAULT)
			return rig_error_set(err, RIG_EDEVICE,
					     "wheel: fault code %u", in.fault);
		if (in.seq == w->seq && !(in.flags & RIG_WHEEL_MOVING) &&
		    in.slot == slot) {
			w->slot = slot;
			return RIG_OK;
		}
		rig_hal_sleep(w->hal, WHEEL_POLL_MS * 1e-3);
	}
	w->slot = -1;
	return rig_error_set(err, RIG_ETIMEOUT,
			     "wheel: slot %d not reached within %.1f s", slot,
			     w->cfg->move_timeout_s);
}

int rig_wheel_count(struct rig_wheel *w, int *n_slots, struct rig_error *err)
{
	struct rig_wheel_in in;
	double t_end = rig_hal_now(w->hal) + w->cfg->move_timeout_s;
	int rc;

	/* A stale answer to an earlier QUERY carries another sequence. */
	while (rig_hal_now(w->hal) <= t_end) {
		rc = query(w, &in, err);
		if (rc == RIG_ETIMEOUT)
			continue;
		if (rc != RIG_OK)
			return rc;
		if (in.seq == w->seq) {
			*n_slots = in.n_slots;
			return RIG_OK;
		}
	}
	return rig_error_set(err, RIG_ETIMEOUT,
			     "wheel: no answer to QUERY within %.1f s",
			     w->cfg->move_timeout_s);
}

void rig_wheel_close(struct rig_wheel *w)
{
	rig_hal_hid_close(&w->hid);
}
