/*
 * framelink.c - encode and check camera commands and frames (framelink.h).
 * The CRC is zlib's crc32 (IEEE 802.3 polynomial), not a local one.
 */
#include <string.h>
#include <zlib.h>

#include "rig/bytes.h"
#include "rig/framelink.h"
#include "rig/status.h"

static const uint8_t cmd_magic[4] = { 'S', 'T', 'C', '1' };
static const uint8_t frame_magic[4] = { 'S', 'T', 'F', '1' };

void rig_fl_cmd_encode(const struct rig_fl_cmd *c, uint8_t out[RIG_FL_CMD_LEN])
{
	int i;

	memset(out, 0, RIG_FL_CMD_LEN);
	memcpy(out, cmd_magic, 4);
	out[4] = c->opcode;
	rig_put_u16(out + 6, c->n_rows);
	rig_put_u32(out + 8, c->arg);
	rig_put_u16(out + 12, c->col0);
	rig_put_u16(out + 14, c->n_cols);
	for (i = 0; i < RIG_FL_CMD_ROWS_MAX && i < c->n_rows; i++)
		rig_put_u16(out + 16 + 2 * i, c->rows[i]);
}

int rig_fl_cmd_decode(const uint8_t *buf, size_t len, struct rig_fl_cmd *c)
{
	int i;

	if (len != RIG_FL_CMD_LEN || memcmp(buf, cmd_magic, 4) != 0)
		return RIG_EPARSE;
	memset(c, 0, sizeof(*c));
	c->opcode = buf[4];
	c->n_rows = rig_get_u16(buf + 6);
	c->arg = rig_get_u32(buf + 8);
	c->col0 = rig_get_u16(buf + 12);
	c->n_cols = rig_get_u16(buf + 14);
	if (c->opcode < RIG_FL_SET_EXPOSURE || c->opcode > RIG_FL_RESEND)
		return RIG_EPARSE;
	if (c->opcode != RIG_FL_SET_WINDOW)
		return RIG_OK;
	if (c->n_rows == 0 || c->n_rows > RIG_FL_CMD_ROWS_MAX ||
	    c->n_cols == 0 || (uint32_t)c->col0 + c->n_cols > RIG_FL_SENSOR_COLS)
		return RIG_EPARSE;
	for (i = 0; i < c->n_rows; i++) {
		c->rows[i] = rig_get_u16(buf + 16 + 2 * i);
		if (c->rows[i] >= RIG_FL_SENSOR_ROWS ||
		    (i > 0 && c->rows[i] <= c->rows[i - 1]))
			return RIG_EPARSE;
	}
	return RIG_OK;
}

size_t rig_fl_frame_len(const struct rig_fl_header *h)
{
	return RIG_FL_HEADER_LEN + (size_t)h->payload_len + RIG_FL_CRC_LEN;
}

int rig_fl_header_decode(const uint8_t *buf, size_t len,
			 struct rig_fl_header *h)
{
	if (len < RIG_FL_HEADER_LEN)
		return RIG_EAGAIN;
	if (memcmp(buf, frame_magic, 4) != 0)
		return RIG_EPROTO;
	h->seq = rig_get_u32(buf + 4);
	h->exposure_us = rig_get_u32(buf + 8);
	h->n_rows = rig_get_u16(buf + 12);
	h->n_cols = rig_get_u16(buf + 14);
	h->col0 = rig_get_u16(buf + 16);
	h->bits = rig_get_u16(buf + 18);
	h->flags = rig_get_u16(buf + 20);
	h->payload_len = rig_get_u32(buf + 24);
	if (h->n_rows == 0 || h->n_rows > RIG_FL_SENSOR_ROWS ||
	    h->n_cols == 0 || (uint32_t)h->col0 + h->n_cols > RIG_FL_SENSOR_COLS ||
	    h->bits == 0 || h->bits > 16 ||
	    h->payload_len != (uint32_t)h->n_rows * (2u + 2u * h->n_cols))
		return RIG_EPROTO;
	return RIG_OK;
}

static int check_rows(const uint8_t *p, const struct rig_fl_header *h,
		      uint16_t *rows_out, uint16_t *px_out)
{
	uint32_t limit = h->bits == 16 ? 0x10000u : (1u << h->bits);
	int prev = -1, r, c;

	for (r = 0; r < h->n_rows; r++) {
		int idx = rig_get_u16(p);

		if (idx >= RIG_FL_SENSOR_ROWS || idx <= prev)
			return RIG_EPROTO;
		prev = idx;
		if (rows_out)
			rows_out[r] = (uint16_t)idx;
		p += 2;
		for (c = 0; c < h->n_cols; c++, p += 2) {
			uint16_t v = rig_get_u16(p);

			if (v >= limit)
				return RIG_EPROTO;
			if (px_out)
				px_out[(size_t)r * h->n_cols + c] = v;
		}
	}
	return RIG_OK;
}

int rig_fl_frame_decode(const uint8_t *buf, size_t len,
			struct rig_fl_header *h, uint16_t *rows_out,
			uint16_t *px_out)
{
	size_t body;
	uLong crc;
	int rc;

	rc = rig_fl_header_decode(buf, len, h);
	if (rc != RIG_OK)
		return rc;
	if (len < rig_fl_frame_len(h))
		return RIG_EAGAIN;
	if (len > rig_fl_frame_len(h))
		return RIG_EPROTO;
	body = RIG_FL_HEADER_LEN + h->payload_len;
	crc = crc32(0L, Z_NULL, 0);
	crc = crc32(crc, buf, (uInt)body);
	if ((uint32_t)crc != rig_get_u32(buf + body))
		return RIG_ECRC;
	return check_rows(buf + RIG_FL_HEADER_LEN, h, rows_out, px_out);
}

size_t rig_fl_frame_encode(const struct rig_fl_header *h,
			   const uint16_t *rows, const uint16_t *px,
			   uint8_t *out, size_t cap)
{
	size_t n = rig_fl_frame_len(h), body;
	uint8_t *p = out + RIG_FL_HEADER_LEN;
	uLong crc;
	int r, c;

	if (cap < n)
		return 0;
	memset(out, 0, RIG_FL_HEADER_LEN);
	memcpy(out, frame_magic, 4);
	rig_put_u32(out + 4, h->seq);
	rig_put_u32(out + 8, h->exposure_us);
	rig_put_u16(out + 12, h->n_rows);
	rig_put_u16(out + 14, h->n_cols);
	rig_put_u16(out + 16, h->col0);
	rig_put_u16(out + 18, h->bits);
	rig_put_u16(out + 20, h->flags);
	rig_put_u32(out + 24, h->payload_len);
	for (r = 0; r < h->n_rows; r++) {
		rig_put_u16(p, rows[r]);
		p += 2;
		for (c = 0; c < h->n_cols; c++, p += 2)
			rig_put_u16(p, px[(size_t)r * h->n_cols + c]);
	}
	body = RIG_FL_HEADER_LEN + h->payload_len;
	crc = crc32(crc32(0L, Z_NULL, 0), out, (uInt)body);
	rig_put_u32(out + body, (uint32_t)crc);
	return n;
}
