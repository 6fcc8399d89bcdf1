/*
 * sim_camera.c - device side of the camera frame link (framelink.h).
 * A TRIGGER exposes on the virtual clock, renders the frame from the
 * virtual lab with the lab state the backend passes in (stage angle, ND
 * slot, GPIO lines: struct sim_lab_view), encodes it with its CRC32 and
 * queues it on the bulk IN endpoint.  Faults: a CRC fault flips one
 * payload byte of that transmission (value >= 1: re-sends too); timeout
 * or stall loses the frame; disconnect unplugs the camera.
 */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "rig/sim_devices.h"
#include "rig/status.h"
#include "rig/vlab.h"

#define READOUT_S 0.02

static int ensure_buffers(struct sim_camera *c, size_t n)
{
	if (n <= c->cap)
		return RIG_OK;
	free(c->clean);
	free(c->wire);
	c->clean = malloc(n);
	c->wire = malloc(n);
	c->cap = c->clean && c->wire ? n : 0;
	return c->cap ? RIG_OK : RIG_ENOMEM;
}

static void real_delay(double s)
{
	struct timespec ts;

	if (s <= 0)
		return;
	ts.tv_sec = (time_t)s;
	ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
	nanosleep(&ts, NULL);
}

static int render(struct sim_camera *c, const struct rig_sim_core *core,
		  const struct sim_lab_view *lab, uint32_t seq)
{
	struct rig_fl_header h;
	struct rig_vlab_state st;
	size_t npx = (size_t)c->window.n_rows * c->window.n_cols;
	uint16_t *px;
	int rc;

	memset(&h, 0, sizeof(h));
	h.seq = seq;
	h.exposure_us = c->exposure_us;
	h.n_rows = c->window.n_rows;
	h.n_cols = c->window.n_cols;
	h.col0 = c->window.col0;
	/* The ADC's width is what the virtual lab clips at: 4095 is
	 * 12 bits, so the frames tell the host what they can hold. */
	for (h.bits = 1; h.bits < 16 &&
	     (1L << h.bits) - 1 < core->cfg->sim.vlab.sat_dn; h.bits++)
		;
	h.payload_len = (uint32_t)h.n_rows * (2u + 2u * h.n_cols);
	rc = ensure_buffers(c, rig_fl_frame_len(&h));
	px = malloc(npx * sizeof(*px));
	if (rc != RIG_OK || !px) {
		free(px);
		return RIG_ENOMEM;
	}
	st.theta_deg = lab->theta_deg;
	st.t_exp_s = c->exposure_us * 1e-6;
	st.nd_trans = lab->nd_trans;
	st.t_s = core->t_s;
	st.lamp_on = lab->lamp_on;
	st.beam_blocked = lab->beam_blocked;
	st.shutter_open = lab->shutter_open;
	rig_vlab_render(&core->cfg->sim.vlab, &st, c->window.rows, h.n_rows,
			h.col0, h.n_cols, ++c->frames, px);
	c->len = rig_fl_frame_encode(&h, c->window.rows, px, c->clean, c->cap);
	free(px);
	return RIG_OK;
}

static void send_copy(struct sim_camera *c, int corrupt)
{
	memcpy(c->wire, c->clean, c->len);
	if (corrupt)
		c->wire[RIG_FL_HEADER_LEN + 3] ^= 0x10;	/* a pixel bit */
	c->sent = 0;
	c->queued = 1;
}

static int trigger(struct sim_camera *c, struct rig_sim_core *core,
		   const struct sim_lab_view *lab, uint32_t seq)
{
	double persist = 0;
	int kind = rig_sim_core_event(core, RIG_DEV_CAMERA, &persist), rc;

	c->queued = 0;
	if (core->gone[RIG_DEV_CAMERA])
		return RIG_EDISCONNECT;
	if (c->window.n_rows == 0 || c->exposure_us == 0)
		return RIG_OK;	/* not configured: no frame comes */
	core->t_s += c->exposure_us * 1e-6 + READOUT_S;
	real_delay(core->cfg->sim.real_delay_s);
	if (kind == RIG_FAULT_TIMEOUT || kind == RIG_FAULT_STALL)
		return RIG_OK;
	rc = render(c, core, lab, seq);
	if (rc == RIG_OK)
		send_copy(c, kind == RIG_FAULT_CRC);
	c->corrupt_resends = (kind == RIG_FAULT_CRC && persist >= 1);
	return rc;
}

int rig_sim_camera_write(struct sim_camera *c, struct rig_sim_core *core,
			 const struct sim_lab_view *lab, const uint8_t *buf,
			 size_t len)
{
	struct rig_fl_cmd cmd;

	if (rig_fl_cmd_decode(buf, len, &cmd) != RIG_OK)
		return RIG_OK;	/* the camera drops what it cannot parse */
	switch (cmd.opcode) {
	case RIG_FL_SET_EXPOSURE:
		c->exposure_us = cmd.arg;
		break;
	case RIG_FL_SET_WINDOW:
		c->window = cmd;
		break;
	case RIG_FL_TRIGGER:
		return trigger(c, core, lab, cmd.arg);
	case RIG_FL_RESEND:
		if (c->len > 0)
			send_copy(c, c->corrupt_resends);
		break;
	default:
		break;
	}
	return RIG_OK;
}

int rig_sim_camera_read(struct sim_camera *c, struct rig_sim_core *core,
			uint8_t *buf, size_t cap, size_t *got,
			unsigned timeout_ms)
{
	size_t n;

	if (!c->queued) {
		core->t_s += timeout_ms * 1e-3;
		return RIG_ETIMEOUT;
	}
	n = c->len - c->sent < cap ? c->len - c->sent : cap;
	memcpy(buf, c->wire + c->sent, n);
	c->sent += n;
	if (c->sent >= c->len)
		c->queued = 0;
	*got = n;
	return RIG_OK;
}

void rig_sim_camera_reset(struct sim_camera *c)
{
	c->queued = 0;
}

void rig_sim_camera_fini(struct sim_camera *c)
{
	free(c->clean);
	free(c->wire);
	c->clean = c->wire = NULL;
}
