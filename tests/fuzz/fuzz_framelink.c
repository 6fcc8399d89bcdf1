/*
 * fuzz_framelink.c - libFuzzer target: the camera frame decoder and the
 * command decoder.  The input is also re-signed with a correct CRC32 so
 * the layout checks behind the CRC are reached, not only the CRC.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "rig/bytes.h"
#include "rig/framelink.h"
#include "rig/status.h"

static void decode(const uint8_t *buf, size_t len)
{
	struct rig_fl_header h;
	uint16_t *rows, *px;

	if (rig_fl_frame_decode(buf, len, &h, NULL, NULL) != RIG_OK)
		return;
	/* A valid frame: decode again into exactly sized arrays. */
	rows = malloc((size_t)h.n_rows * sizeof(*rows));
	px = malloc((size_t)h.n_rows * h.n_cols * sizeof(*px));
	if (rows && px &&
	    rig_fl_frame_decode(buf, len, &h, rows, px) != RIG_OK)
		__builtin_trap();
	free(rows);
	free(px);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rig_fl_cmd cmd;
	uint8_t *copy;

	(void)rig_fl_cmd_decode(data, size, &cmd);
	decode(data, size);
	if (size < RIG_FL_HEADER_LEN + RIG_FL_CRC_LEN)
		return 0;
	copy = malloc(size);
	if (!copy)
		return 0;
	memcpy(copy, data, size);
	rig_put_u32(copy + size - 4,
		    (uint32_t)crc32(0, copy, (uInt)(size - 4)));
	decode(copy, size);
	free(copy);
	return 0;
}
