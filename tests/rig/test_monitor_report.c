/*
 * test_monitor_report.c - the monitor photodiode's HID reports
 * (monitor_report.c), byte for byte as docs/rig-hid-wheel.md lays them out.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "rig/monitor_report.h"
#include "rig/status.h"

static void test_monitor_reports_layout(void **state)
{
	static const uint8_t want_out[8] = { 0x04, 0x01, 0x07, 0, 0, 0, 0, 0 };
	static const uint8_t want_in[8] = { 0x05, 0x07, 0x40, 0x42, 0x0F, 0x00,
					    0x00, 0x00 };
	struct rig_monitor_in in = { 7, 0, 1000000 }, back;
	uint8_t buf[8], seq;

	(void)state;
	rig_monitor_out_encode(7, buf);
	assert_memory_equal(buf, want_out, 8);
	assert_int_equal(rig_monitor_out_decode(buf, 8, &seq), RIG_OK);
	assert_int_equal(seq, 7);
	rig_monitor_in_encode(&in, buf);
	assert_memory_equal(buf, want_in, 8);	/* 1e6 pA little-endian */
	assert_int_equal(rig_monitor_in_decode(buf, 8, &back), RIG_OK);
	assert_int_equal(back.current_pa, 1000000);
	buf[6] = 0x02;				/* unknown flag */
	assert_int_equal(rig_monitor_in_decode(buf, 8, &back), RIG_EPROTO);
	buf[6] = 0;
	assert_int_equal(rig_monitor_in_decode(buf, 7, &back), RIG_EPROTO);
	buf[0] = 0x04;
	assert_int_equal(rig_monitor_in_decode(buf, 8, &back), RIG_EPROTO);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_monitor_reports_layout),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
