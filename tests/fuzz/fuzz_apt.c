/*
 * fuzz_apt.c - libFuzzer target: the APT message decoder as the stage
 * driver uses it, draining a byte stream with resync on bad headers;
 * every decoded message must re-encode to the bytes it came from.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "rig/apt.h"
#include "rig/status.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rig_apt_msg m;
	uint8_t again[RIG_APT_HEADER_LEN + RIG_APT_DATA_MAX];
	size_t off = 0, used;
	int32_t pos;

	while (off < size) {
		int rc = rig_apt_decode(data + off, size - off, &m, &used);

		if (rc == RIG_EAGAIN)
			break;
		if (rc != RIG_OK) {
			off++;
			continue;
		}
		if (rig_apt_encode(&m, again, sizeof(again)) != used ||
		    memcmp(again, data + off, used) != 0)
			__builtin_trap();
		(void)rig_apt_position(&m, &pos);
		off += used;
	}
	return 0;
}
