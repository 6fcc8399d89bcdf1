/*
 * camera.c - tracker camera over the frame link (framelink.h): sets the
 * row window and exposure, triggers, reads one frame in bulk chunks and
 * checks it; a frame failing its CRC32 is asked for again (RESEND) up to
 * crc_retries times, so a noisy cable costs time, never a bad frame.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rig/devices.h"

#define CAM_CHUNK 16384
#define CAM_CMD_TIMEOUT_MS 500

static int send_cmd(struct rig_camera *c, const struct rig_fl_cmd *cmd,
		    struct rig_error *err)
{
	uint8_t buf[RIG_FL_CMD_LEN];
	int rc;

	rig_fl_cmd_encode(cmd, buf);
	rc = rig_hal_usb_write(&c->usb, RIG_FL_EP_CMD, buf, sizeof(buf),
			       CAM_CMD_TIMEOUT_MS);
	if (rc != RIG_OK)
		return rig_error_set(err, rc, "camera: command %u: %s",
				     cmd->opcode, rig_status_text(rc));
	return RIG_OK;
}

static int set_window(struct rig_camera *c, struct rig_error *err)
{
	const struct rig_camera_cfg *cfg = c->cfg;
	struct rig_fl_cmd cmd;

	memset(&cmd, 0, sizeof(cmd));
	cmd.opcode = RIG_FL_SET_WINDOW;
	cmd.n_rows = (uint16_t)cfg->n_rows;
	cmd.col0 = (uint16_t)cfg->col0;
	cmd.n_cols = (uint16_t)cfg->n_cols;
	memcpy(cmd.rows, cfg->rows, sizeof(cmd.rows));
	return send_cmd(c, &cmd, err);
}

int rig_camera_open(struct rig_camera *c, const struct rig_hal *hal,
		    const struct rig_camera_cfg *cfg, struct rig_error *err)
{
	struct rig_usb_id id = cfg->usb;
	int rc;

	memset(c, 0, sizeof(*c));
	c->cfg = cfg;
	c->hal = hal;
	c->buf_cap = RIG_FL_HEADER_LEN + RIG_FL_CRC_LEN +
		     (size_t)cfg->n_rows * (2 + 2 * (size_t)cfg->n_cols);
	c->buf = malloc(c->buf_cap);
	if (!c->buf)
		return rig_error_set(err, RIG_ENOMEM, "camera: no memory");
	id.serial = cfg->serial[0] ? cfg->serial : NULL;
	rc = rig_hal_usb_open(hal, &id, &c->usb);
	if (rc != RIG_OK) {
		rig_camera_close(c);
		return rig_error_set(err, rc,
				     "camera: usb %04x:%04x: cannot open: %s",
				     id.vid, id.pid, rig_status_text(rc));
	}
	rc = set_window(c, err);
	if (rc != RIG_OK)
		rig_camera_close(c);
	return rc;
}

int rig_camera_set_exposure(struct rig_camera *c, double t_exp_s,
			    struct rig_error *err)
{
	struct rig_fl_cmd cmd;
	int rc;

	if (!(t_exp_s > 0 && t_exp_s < 4000))
		return rig_error_set(err, RIG_EINVAL,
				     "camera: exposure %g s out of range",
				     t_exp_s);
	memset(&cmd, 0, sizeof(cmd));
	cmd.opcode = RIG_FL_SET_EXPOSURE;
	cmd.arg = (uint32_t)lround(t_exp_s * 1e6);
	rc = send_cmd(c, &cmd, err);
	if (rc == RIG_OK)
		c->exposure_us = cmd.arg;
	return rc;
}

/* Read one frame's bytes into c->buf; returns its length in *len. */
static int read_frame(struct rig_camera *c, size_t *len,
		      struct rig_error *err)
{
	unsigned timeout_ms = (unsigned)(c->exposure_us / 1000 +
					 c->cfg->timeout_s * 1000);
	struct rig_fl_header h;
	size_t want = RIG_FL_HEADER_LEN, have = 0, got;
	int rc;

	while (have < want) {
		size_t ask = want - have < CAM_CHUNK ? want - have : CAM_CHUNK;

		rc = rig_hal_usb_read(&c->usb, RIG_FL_EP_DATA, c->buf + have,
				      ask, &got, timeout_ms);
		if (rc != RIG_OK)
			return rig_error_set(err, rc,
				"camera: frame %u: read: %s", c->seq,
				rig_status_text(rc));
		have += got;
		if (have >= RIG_FL_HEADER_LEN && want == RIG_FL_HEADER_LEN) {
			rc = rig_fl_header_decode(c->buf, have, &h);
			if (rc != RIG_OK || rig_fl_frame_len(&h) > c->buf_cap)
				return rig_error_set(err, RIG_EPROTO,
					"camera: frame %u: bad header",
					c->seq);
			want = rig_fl_frame_len(&h);
		}
	}
	*len = have;
	return RIG_OK;
}

static int check_frame(struct rig_camera *c, size_t len,
		       struct rig_image *img)
{
	struct rig_fl_header h;
	/* First pass checks CRC and layout only, so the row and pixel
	 * arrays are written only once the size is known to fit them. */
	int rc = rig_fl_frame_decode(c->buf, len, &h, NULL, NULL);

	if (rc != RIG_OK)
		return rc;
	if (h.seq != c->seq || h.n_rows != c->cfg->n_rows ||
	    h.n_cols != c->cfg->n_cols || h.col0 != c->cfg->col0 ||
	    h.exposure_us != c->exposure_us)
		return RIG_EPROTO;	/* not the frame we asked for */
	rig_fl_frame_decode(c->buf, len, &h, img->rows, img->px);
	img->n_rows = h.n_rows;
	img->n_cols = h.n_cols;
	img->col0 = h.col0;
	img->t_exp_s = h.exposure_us * 1e-6;
	img->seq = h.seq;
	img->bits = c->bits = h.bits;
	return RIG_OK;
}

int rig_camera_capture(struct rig_camera *c, struct rig_image *img,
		       struct rig_error *err)
{
	struct rig_fl_cmd cmd;
	size_t len = 0;
	int attempt, rc;

	memset(&cmd, 0, sizeof(cmd));
	cmd.opcode = RIG_FL_TRIGGER;
	cmd.arg = ++c->seq;
	rc = send_cmd(c, &cmd, err);
	for (attempt = 0; rc == RIG_OK; attempt++) {
		rc = read_frame(c, &len, err);
		if (rc != RIG_OK)
			return rc;
		rc = check_frame(c, len, img);
		if (rc == RIG_OK)
			return RIG_OK;
		if (rc != RIG_ECRC || attempt >= c->cfg->crc_retries)
			break;
		c->crc_rereads++;
		cmd.opcode = RIG_FL_RESEND;
		rc = send_cmd(c, &cmd, err);
	}
	if (rc == RIG_ECRC)
		return rig_error_set(err, rc,
			"camera: frame %u: CRC mismatch after %d re-reads",
			c->seq, c->cfg->crc_retries);
	return rig_error_set(err, rc, "camera: frame %u: %s", c->seq,
			     rig_status_text(rc));
}

void rig_camera_close(struct rig_camera *c)
{
	rig_hal_usb_close(&c->usb);
	free(c->buf);
	c->buf = NULL;
}
