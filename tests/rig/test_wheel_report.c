/*
 * test_wheel_report.c - the ND wheel's HID reports (wheel_report.c),
 * byte for byte as docs/rig-hid-wheel.md lays them out.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <string.h>

#include "rig/status.h"
#include "rig/wheel_report.h"

static void test_wheel_out_layout(void **state)
{
	static const uint8_t want[8] = { 0x01, 0x01, 0x04, 0x2A, 0, 0, 0, 0 };
	struct rig_wheel_out o = { RIG_WHEEL_GOTO, 4, 42 }, back;
	uint8_t buf[8];

	(void)state;
	rig_wheel_out_encode(&o, buf);
	assert_memory_equal(buf, want, 8);
	assert_int_equal(rig_wheel_out_decode(buf, 8, &back), RIG_OK);
	assert_int_equal(back.slot, 4);
	buf[1] = 7;
	assert_int_equal(rig_wheel_out_decode(buf, 8, &back), RIG_EPROTO);
}

static void test_wheel_in_layout_and_checks(void **state)
{
	static const uint8_t want[8] = { 0x02, 0x03, 0x02, 0x09, 0x06, 0, 0,
					 0 };
	struct rig_wheel_in in = { RIG_WHEEL_MOVING | RIG_WHEEL_HOMED, 2, 9, 6,
				   0 }, back;
	uint8_t buf[8];

	(void)state;
	rig_wheel_in_encode(&in, buf);
	assert_memory_equal(buf, want, 8);
	assert_int_equal(rig_wheel_in_decode(buf, 8, &back), RIG_OK);
	assert_int_equal(back.seq, 9);
	assert_int_equal(rig_wheel_in_decode(buf, 7, &back), RIG_EPROTO);
	buf[2] = 6;				/* slot == count */
	assert_int_equal(rig_wheel_in_decode(buf, 8, &back), RIG_EPROTO);
	buf[2] = RIG_WHEEL_SLOT_UNKNOWN;
	assert_int_equal(rig_wheel_in_decode(buf, 8, &back), RIG_OK);
	buf[4] = 13;				/* too many slots */
	assert_int_equal(rig_wheel_in_decode(buf, 8, &back), RIG_EPROTO);
	buf[4] = 6;
	buf[1] = 0x80;				/* unknown flag */
	assert_int_equal(rig_wheel_in_decode(buf, 8, &back), RIG_EPROTO);
	buf[1] = 0;
	buf[0] = 0x01;				/* wrong report id */
	assert_int_equal(rig_wheel_in_decode(buf, 8, &back), RIG_EPROTO);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_wheel_out_layout),
		cmocka_unit_test(test_wheel_in_layout_and_checks),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
