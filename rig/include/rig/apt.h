/*
 * apt.h - the Thorlabs APT motion-controller message format, as spoken by
 * K10CR1-class rotation mounts over their FTDI bridge.
 *
 * [Thorlabs, "APT Communications Protocol", issue 23, §2.2]: a message is
 * a 6-byte header {message id (LE16), param1, param2, dest, source}; when
 * bit 7 of dest is set, bytes 2-3 instead hold the length of a data
 * packet that follows.  Numbers are little-endian; positions are signed
 * 32-bit encoder counts.
 */
#ifndef RIG_APT_H
#define RIG_APT_H

#include <stddef.h>
#include <stdint.h>

#define RIG_APT_HEADER_LEN 6
#define RIG_APT_DATA_MAX 96	/* longest message we accept (HW_GET_INFO: 84) */
#define RIG_APT_LONG_FLAG 0x80

/* Addresses [protocol §2.3]. */
#define RIG_APT_HOST 0x01
#define RIG_APT_RACK 0x11
#define RIG_APT_USB_UNIT 0x50

/* Message ids used here [protocol §3-4]. */
#define RIG_APT_HW_RESPONSE 0x0080
#define RIG_APT_HW_RICHRESPONSE 0x0081
#define RIG_APT_HW_NO_FLASH_PROGRAMMING 0x0018
#define RIG_APT_MOT_REQ_POSCOUNTER 0x0411
#define RIG_APT_MOT_GET_POSCOUNTER 0x0412
#define RIG_APT_MOT_MOVE_HOME 0x0443
#define RIG_APT_MOT_MOVE_HOMED 0x0444
#define RIG_APT_MOT_MOVE_ABSOLUTE 0x0453
#define RIG_APT_MOT_MOVE_COMPLETED 0x0464
#define RIG_APT_MOT_MOVE_STOP 0x0465
#define RIG_APT_MOT_MOVE_STOPPED 0x0466

/* Length of the status block carried by MOVE_COMPLETED / MOVE_STOPPED. */
#define RIG_APT_STATUS_LEN 14
#define RIG_APT_CHAN1 0x01

struct rig_apt_msg {
	uint16_t id;
	uint8_t param1, param2;	/* short form only */
	uint8_t dest, source;	/* dest without the long flag */
	uint16_t data_len;	/* 0 = short form */
	uint8_t data[RIG_APT_DATA_MAX];
};

/*
 * Encode m into buf; returns the byte count, or 0 when cap is too small
 * or data_len exceeds RIG_APT_DATA_MAX.
 */
size_t rig_apt_encode(const struct rig_apt_msg *m, uint8_t *buf, size_t cap);

/*
 * Decode one message from the front of buf.  RIG_OK with *used bytes
 * consumed; RIG_EAGAIN when more bytes are needed; RIG_EPROTO for a header
 * that no APT unit sends (unknown address, oversize packet): the caller
 * resynchronises by dropping a byte.
 */
int rig_apt_decode(const uint8_t *buf, size_t len, struct rig_apt_msg *m,
		   size_t *used);

/* Short message (no data) from host to the USB unit. */
void rig_apt_short(struct rig_apt_msg *m, uint16_t id, uint8_t p1,
		   uint8_t p2);

/* MOVE_ABSOLUTE: channel and absolute position in counts [§4 0x0453]. */
void rig_apt_move_absolute(struct rig_apt_msg *m, int32_t counts);

/*
 * Position in counts from a GET_POSCOUNTER, MOVE_COMPLETED, MOVE_HOMED-
 * with-status or MOVE_STOPPED message; RIG_EPROTO when m carries none.
 */
int rig_apt_position(const struct rig_apt_msg *m, int32_t *counts);

#endif /* RIG_APT_H */
