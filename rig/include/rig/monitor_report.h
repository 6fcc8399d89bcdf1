/*
 * monitor_report.h - HID reports of the monitor photodiode that watches
 * the lamp for drift (layout in docs/rig-hid-wheel.md, "Monitor").
 *
 * Output report 0x04 (host to monitor), 8 bytes with the id:
 *   id, command (1 READ), sequence, 0 x5.
 * Input report 0x05 (monitor to host), 8 bytes with the id:
 *   id, sequence echo, photocurrent in pA (LE32), flags (bit0 over-range),
 *   0.
 */
#ifndef RIG_MONITOR_REPORT_H
#define RIG_MONITOR_REPORT_H

#include <stddef.h>
#include <stdint.h>

#define RIG_MONITOR_REPORT_LEN 8
#define RIG_MONITOR_OUT_ID 0x04
#define RIG_MONITOR_IN_ID 0x05
#define RIG_MONITOR_READ 1
#define RIG_MONITOR_OVERRANGE 0x01

struct rig_monitor_in {
	uint8_t seq, flags;
	uint32_t current_pa;
};

void rig_monitor_out_encode(uint8_t seq, uint8_t buf[RIG_MONITOR_REPORT_LEN]);
/* RIG_OK with *seq for a READ request, RIG_EPROTO otherwise. */
int rig_monitor_out_decode(const uint8_t *buf, size_t len, uint8_t *seq);
void rig_monitor_in_encode(const struct rig_monitor_in *in,
			   uint8_t buf[RIG_MONITOR_REPORT_LEN]);
int rig_monitor_in_decode(const uint8_t *buf, size_t len,
			  struct rig_monitor_in *in);

#endif /* RIG_MONITOR_REPORT_H */
