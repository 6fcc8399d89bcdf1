/*
 * wheel_report.h - HID reports of the ND filter wheel (layout documented
 * in docs/rig-hid-wheel.md).
 *
 * Output report 0x01 (host to wheel), 8 bytes with the id:
 *   id, command (1 GOTO, 2 QUERY, 3 HOME), slot, sequence, 0 x4.
 * Input report 0x02 (wheel to host), 8 bytes with the id:
 *   id, flags (bit0 moving, bit1 homed, bit2 fault), slot (0xFF unknown),
 *   sequence echo, slot count, fault code, 0, 0.
 */
#ifndef RIG_WHEEL_REPORT_H
#define RIG_WHEEL_REPORT_H

#include <stddef.h>
#include <stdint.h>

#define RIG_WHEEL_REPORT_LEN 8
#define RIG_WHEEL_OUT_ID 0x01
#define RIG_WHEEL_IN_ID 0x02
#define RIG_WHEEL_SLOTS_MAX 12
#define RIG_WHEEL_SLOT_UNKNOWN 0xFF

enum rig_wheel_cmd { RIG_WHEEL_GOTO = 1, RIG_WHEEL_QUERY = 2,
		     RIG_WHEEL_HOME = 3 };

#define RIG_WHEEL_MOVING 0x01
#define RIG_WHEEL_HOMED 0x02
#define RIG_WHEEL_FAULT 0x04

struct rig_wheel_out {
	uint8_t cmd, slot, seq;
};

struct rig_wheel_in {
	uint8_t flags, slot, seq, n_slots, fault;
};

void rig_wheel_out_encode(const struct rig_wheel_out *o,
			  uint8_t buf[RIG_WHEEL_REPORT_LEN]);
int rig_wheel_out_decode(const uint8_t *buf, size_t len,
			 struct rig_wheel_out *o);
void rig_wheel_in_encode(const struct rig_wheel_in *in,
			 uint8_t buf[RIG_WHEEL_REPORT_LEN]);
/* RIG_EPROTO for a wrong id, length, slot count or slot. */
int rig_wheel_in_decode(const uint8_t *buf, size_t len,
			struct rig_wheel_in *in);

#endif /* RIG_WHEEL_REPORT_H */
