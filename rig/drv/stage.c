/*
 * stage.c - rotation stage driver: Thorlabs APT messages (apt.h) over the
 * FTDI bridge (ftdi.c).  Moves are absolute in encoder counts; every move
 * waits for MOVE_COMPLETED and then checks the position counter, so a
 * stage that stops short is caught (RIG_ETARGET), not believed.
 */
#include <math.h>
#include <string.h>

#include "rig/apt.h"
#include "rig/devices.h"

#define STAGE_POLL_MS 50

int rig_stage_open(struct rig_stage *s, const struct rig_hal *hal,
		   const struct rig_stage_cfg *cfg, struct rig_error *err)
{
	struct rig_usb_id id = cfg->usb;
	int rc;

	memset(s, 0, sizeof(*s));
	s->cfg = cfg;
	s->hal = hal;
	id.serial = cfg->serial[0] ? cfg->serial : NULL;
	rc = rig_hal_usb_open(hal, &id, &s->usb);
	if (rc == RIG_OK)
		rc = rig_ftdi_setup(&s->usb, id.interface);
	if (rc != RIG_OK) {
		rig_hal_usb_close(&s->usb);
		return rig_error_set(err, rc,
				     "stage: usb %04x:%04x: cannot open: %s",
				     id.vid, id.pid, rig_status_text(rc));
	}
	return RIG_OK;
}

static int send_msg(struct rig_stage *s, const struct rig_apt_msg *m,
		    struct rig_error *err)
{
	uint8_t buf[RIG_APT_HEADER_LEN + RIG_APT_DATA_MAX];
	size_t n = rig_apt_encode(m, buf, sizeof(buf));
	int rc = rig_ftdi_write(&s->usb, buf, n);

	if (rc != RIG_OK)
		return rig_error_set(err, rc, "stage: send 0x%04x: %s", m->id,
				     rig_status_text(rc));
	return RIG_OK;
}

/* Take one message out of the receive buffer; resync past bad bytes. */
static int next_buffered(struct rig_stage *s, struct rig_apt_msg *m)
{
	size_t used;
	int rc;

	while (s->rx_len > 0) {
		rc = rig_apt_decode(s->rx, s->rx_len, m, &used);
		if (rc == RIG_EAGAIN)
			return RIG_EAGAIN;
		if (rc != RIG_OK)
			used = 1;	/* garbage: drop a byte */
		memmove(s->rx, s->rx + used, s->rx_len - used);
		s->rx_len -= used;
		if (rc == RIG_OK)
			return RIG_OK;
	}
	return RIG_EAGAIN;
}

/* Wait for message `id`; a HW_RESPONSE from the unit is its error. */
static int wait_for(struct rig_stage *s, uint16_t id, double timeout_s,
		    struct rig_apt_msg *m, struct rig_error *err)
{
	double t_end = rig_hal_now(s->hal) + timeout_s;
	size_t got;
	int rc;

	for (;;) {
		while (next_buffered(s, m) == RIG_OK) {
			if (m->id == id)
				return RIG_OK;
			if (m->id == RIG_APT_HW_RESPONSE ||
			    m->id == RIG_APT_HW_RICHRESPONSE)
				return rig_error_set(err, RIG_EDEVICE,
					"stage: controller reported error "
					"(message 0x%04x)", m->id);
		}
		if (rig_hal_now(s->hal) > t_end)
			return rig_error_set(err, RIG_ETIMEOUT,
				"stage: no reply 0x%04x within %.1f s", id,
				timeout_s);
		rc = rig_ftdi_read(&s->usb, s->rx + s->rx_len,
				   sizeof(s->rx) - s->rx_len, &got,
				   STAGE_POLL_MS);
		if (rc == RIG_EPROTO) {
			s->rx_len = 0;	/* overflow of garbage */
			continue;
		}
		if (rc != RIG_OK && rc != RIG_ETIMEOUT)
			return rig_error_set(err, rc, "stage: read: %s",
					     rig_status_text(rc));
		s->rx_len += got;
	}
}

int rig_stage_position(struct rig_stage *s, double *theta_deg,
		       struct rig_error *err)
{
	struct rig_apt_msg m;
	int32_t counts;
	int rc;

	rig_apt_short(&m, RIG_APT_MOT_REQ_POSCOUNTER, RIG_APT_CHAN1, 0);
	rc = send_msg(s, &m, err);
	if (rc == RIG_OK)
		rc = wait_for(s, RIG_APT_MOT_GET_POSCOUNTER, 1.0, &m, err);
	if (rc != RIG_OK)
		return rc;
	if (rig_apt_position(&m, &counts) != RIG_OK)
		return rig_error_set(err, RIG_EPROTO,
				     "stage: short GET_POSCOUNTER");
	*theta_deg = counts / s->cfg->counts_per_deg;
	return RIG_OK;
}

int rig_stage_home(struct rig_stage *s, struct rig_error *err)
{
	struct rig_apt_msg m;
	int rc;

	s->homed = 0;
	s->rx_len = 0;
	rig_apt_short(&m, RIG_APT_MOT_MOVE_HOME, RIG_APT_CHAN1, 0);
	rc = send_msg(s, &m, err);
	if (rc == RIG_OK)
		rc = wait_for(s, RIG_APT_MOT_MOVE_HOMED,
			      s->cfg->move_timeout_s * 2, &m, err);
	if (rc == RIG_OK)
		s->homed = 1;
	return rc;
}

int rig_stage_move(struct rig_stage *s, double theta_deg,
		   struct rig_error *err)
{
	struct rig_apt_msg m;
	double at;
	int rc;

	if (!(theta_deg >= s->cfg->min_deg && theta_deg <= s->cfg->max_deg))
		return rig_error_set(err, RIG_EINTERLOCK,
			"stage: angle %g deg outside limits [%g, %g] deg",
			theta_deg, s->cfg->min_deg, s->cfg->max_deg);
	if (!s->homed)
		return rig_error_set(err, RIG_ESTATE,
				     "stage: not homed; home it first");
	rig_apt_move_absolute(&m, (int32_t)lround(theta_deg *
						  s->cfg->counts_per_deg));
	rc = send_msg(s, &m, err);
	if (rc == RIG_OK)
		rc = wait_for(s, RIG_APT_MOT_MOVE_COMPLETED,
			      s->cfg->move_timeout_s, &m, err);
	if (rc == RIG_OK)
		rc = rig_stage_position(s, &at, err);
	if (rc != RIG_OK)
		return rc;
	s->readback_deg = at;
	if (fabs(at - theta_deg) > s->cfg->tol_deg)
		return rig_error_set(err, RIG_ETARGET,
			"stage: stopped at %.4f deg, target %.4f deg", at,
			theta_deg);
	return RIG_OK;
}

int rig_stage_stop(struct rig_stage *s, struct rig_error *err)
{
	struct rig_apt_msg m;

	/* Stop mode 2 = profiled (controlled) stop [protocol 0x0465]. */
	rig_apt_short(&m, RIG_APT_MOT_MOVE_STOP, RIG_APT_CHAN1, 2);
	return send_msg(s, &m, err);
}

void rig_stage_close(struct rig_stage *s)
{
	rig_hal_usb_close(&s->usb);
}
