/*
 * fuzz_wheel_report.c - libFuzzer target: the HID report decoders of the
 * ND wheel and the lamp monitor; an accepted report must re-encode to the
 * same bytes.
 */
#include <stdint.h>
#include <string.h>

#include "rig/monitor_report.h"
#include "rig/status.h"
#include "rig/wheel_report.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rig_wheel_in in;
	struct rig_wheel_out out;
	struct rig_monitor_in mon;
	uint8_t again[RIG_WHEEL_REPORT_LEN], seq;

	if (rig_wheel_in_decode(data, size, &in) == RIG_OK) {
		rig_wheel_in_encode(&in, again);
		if (memcmp(again, data, 6) != 0)
			__builtin_trap();
	}
	if (rig_wheel_out_decode(data, size, &out) == RIG_OK) {
		rig_wheel_out_encode(&out, again);
		if (memcmp(again, data, 4) != 0)
			__builtin_trap();
	}
	if (rig_monitor_in_decode(data, size, &mon) == RIG_OK) {
		rig_monitor_in_encode(&mon, again);
		if (memcmp(again, data, RIG_MONITOR_REPORT_LEN) != 0)
			__builtin_trap();
	}
	(void)rig_monitor_out_decode(data, size, &seq);
	return 0;
}
