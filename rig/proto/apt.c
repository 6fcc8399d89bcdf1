/*
 * apt.c - encode and decode Thorlabs APT messages (see apt.h).
 */
#include <string.h>

#include "rig/apt.h"
#include "rig/bytes.h"
#include "rig/status.h"

/* Addresses an APT unit or host uses [protocol §2.3]: host, rack,
 * bays 0x21-0x2A, generic USB unit. */
static int address_valid(uint8_t a)
{
	return a == RIG_APT_HOST || a == RIG_APT_RACK ||
	       (a >= 0x21 && a <= 0x2A) || a == RIG_APT_USB_UNIT;
}

size_t rig_apt_encode(const struct rig_apt_msg *m, uint8_t *buf, size_t cap)
{
	size_t n = RIG_APT_HEADER_LEN + m->data_len;

	if (m->data_len > RIG_APT_DATA_MAX || cap < n)
		return 0;
	rig_put_u16(buf, m->id);
	if (m->data_len) {
		rig_put_u16(buf + 2, m->data_len);
		buf[4] = (uint8_t)(m->dest | RIG_APT_LONG_FLAG);
		memcpy(buf + RIG_APT_HEADER_LEN, m->data, m->data_len);
	} else {
		buf[2] = m->param1;
		buf[3] = m->param2;
		buf[4] = m->dest;
	}
	buf[5] = m->source;
	return n;
}

int rig_apt_decode(const uint8_t *buf, size_t len, struct rig_apt_msg *m,
		   size_t *used)
{
	uint8_t dest;
	size_t data_len = 0;

	*used = 0;
	if (len < RIG_APT_HEADER_LEN)
		return RIG_EAGAIN;
	dest = buf[4];
	if (!address_valid(dest & (uint8_t)~RIG_APT_LONG_FLAG) ||
	    !address_valid(buf[5]))
		return RIG_EPROTO;
	if (dest & RIG_APT_LONG_FLAG) {
		data_len = rig_get_u16(buf + 2);
		if (data_len == 0 || data_len > RIG_APT_DATA_MAX)
			return RIG_EPROTO;
		if (len < RIG_APT_HEADER_LEN + data_len)
			return RIG_EAGAIN;
	}
	memset(m, 0, sizeof(*m));
	m->id = rig_get_u16(buf);
	m->dest = dest & (uint8_t)~RIG_APT_LONG_FLAG;
	m->source = buf[5];
	m->data_len = (uint16_t)data_len;
	if (data_len)
		memcpy(m->data, buf + RIG_APT_HEADER_LEN, data_len);
	else {
		m->param1 = buf[2];
		m->param2 = buf[3];
	}
	*used = RIG_APT_HEADER_LEN + data_len;
	return RIG_OK;
}

void rig_apt_short(struct rig_apt_msg *m, uint16_t id, uint8_t p1, uint8_t p2)
{
	memset(m, 0, sizeof(*m));
	m->id = id;
	m->param1 = p1;
	m->param2 = p2;
	m->dest = RIG_APT_USB_UNIT;
	m->source = RIG_APT_HOST;
}

void rig_apt_move_absolute(struct rig_apt_msg *m, int32_t counts)
{
	memset(m, 0, sizeof(*m));
	m->id = RIG_APT_MOT_MOVE_ABSOLUTE;
	m->dest = RIG_APT_USB_UNIT;
	m->source = RIG_APT_HOST;
	m->data_len = 6;
	rig_put_u16(m->data, RIG_APT_CHAN1);
	rig_put_u32(m->data + 2, (uint32_t)counts);
}

int rig_apt_position(const struct rig_apt_msg *m, int32_t *counts)
{
	switch (m->id) {
	case RIG_APT_MOT_GET_POSCOUNTER:
		if (m->data_len < 6)
			return RIG_EPROTO;
		break;
	case RIG_APT_MOT_MOVE_COMPLETED:
	case RIG_APT_MOT_MOVE_STOPPED:
	case RIG_APT_MOT_MOVE_HOMED:
		if (m->data_len < RIG_APT_STATUS_LEN)
			return RIG_EPROTO;
		break;
	default:
		return RIG_EPROTO;
	}
	/* Channel ident (2 bytes), then the position (signed 32-bit). */
	*counts = (int32_t)rig_get_u32(m->data + 2);
	return RIG_OK;
}
