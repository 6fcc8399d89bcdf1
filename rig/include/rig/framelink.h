/*
 * framelink.h - the tracker camera's frame link over USB bulk transfers
 * (layout documented in docs/rig-camera-framing.md).
 *
 * Host to camera, bulk OUT endpoint 0x01: fixed 64-byte commands
 *   "STC1", opcode, 0, n_rows (LE16), arg (LE32), col0 (LE16),
 *   n_cols (LE16), rows[24] (LE16 each).
 * Camera to host, bulk IN endpoint 0x82, one frame per TRIGGER/RESEND:
 *   32-byte header, n_rows rows of {row index LE16, n_cols pixels LE16},
 *   then CRC32 (zlib's, LE32) over header and rows.
 */
#ifndef RIG_FRAMELINK_H
#define RIG_FRAMELINK_H

#include <stddef.h>
#include <stdint.h>

#define RIG_FL_EP_CMD 0x01
#define RIG_FL_EP_DATA 0x82
#define RIG_FL_CMD_LEN 64
#define RIG_FL_CMD_ROWS_MAX 24
#define RIG_FL_HEADER_LEN 32
#define RIG_FL_CRC_LEN 4
#define RIG_FL_SENSOR_ROWS 1944	/* st16-like detector */
#define RIG_FL_SENSOR_COLS 2592

enum rig_fl_opcode {
	RIG_FL_SET_EXPOSURE = 1,	/* arg = exposure in microseconds */
	RIG_FL_SET_WINDOW = 2,		/* rows[n_rows], col0, n_cols */
	RIG_FL_TRIGGER = 3,		/* arg = frame sequence number */
	RIG_FL_RESEND = 4,		/* arg = sequence of the frame to resend */
};

struct rig_fl_cmd {
	uint8_t opcode;
	uint32_t arg;
	uint16_t n_rows, col0, n_cols;
	uint16_t rows[RIG_FL_CMD_ROWS_MAX];
};

struct rig_fl_header {
	uint32_t seq;
	uint32_t exposure_us;
	uint16_t n_rows, n_cols, col0;
	uint16_t bits;		/* ADC bits: pixels are < 2^bits */
	uint16_t flags;
	uint32_t payload_len;	/* n_rows * (2 + 2 n_cols) */
};

/* Encode / decode a command; decode returns RIG_EPARSE on bad input. */
void rig_fl_cmd_encode(const struct rig_fl_cmd *c, uint8_t out[RIG_FL_CMD_LEN]);
int rig_fl_cmd_decode(const uint8_t *buf, size_t len, struct rig_fl_cmd *c);

/* Bytes of a whole frame with this header (header + rows + CRC). */
size_t rig_fl_frame_len(const struct rig_fl_header *h);

/*
 * Parse and check the 32-byte header (magic, sizes inside the sensor,
 * payload length consistent).  RIG_EAGAIN if len < 32, RIG_EPROTO else.
 */
int rig_fl_header_decode(const uint8_t *buf, size_t len,
			 struct rig_fl_header *h);

/*
 * Check a complete frame: header, CRC32, row indices strictly increasing
 * inside the sensor, pixels below 2^bits.  On RIG_OK, rows_out (n_rows)
 * and px_out (n_rows * n_cols) are filled when not NULL.
 */
int rig_fl_frame_decode(const uint8_t *buf, size_t len,
			struct rig_fl_header *h, uint16_t *rows_out,
			uint16_t *px_out);

/* Encode a frame into out (cap >= rig_fl_frame_len); returns its length. */
size_t rig_fl_frame_encode(const struct rig_fl_header *h,
			   const uint16_t *rows, const uint16_t *px,
			   uint8_t *out, size_t cap);

#endif /* RIG_FRAMELINK_H */
