/*
 * test_apt.c - APT message encoding and decoding (apt.c) against byte
 * strings written out from the Thorlabs protocol document (issue 23):
 * short and long forms, partial input, invalid addresses, oversize.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <string.h>

#include "rig/apt.h"
#include "rig/status.h"

/* MGMSG_MOT_MOVE_HOME for channel 1: 43 04 01 00 50 01 (§ 0x0443). */
static void test_apt_short_form_bytes(void **state)
{
	static const uint8_t want[] = { 0x43, 0x04, 0x01, 0x00, 0x50, 0x01 };
	struct rig_apt_msg m;
	uint8_t buf[16];

	(void)state;
	rig_apt_short(&m, RIG_APT_MOT_MOVE_HOME, 1, 0);
	assert_int_equal(rig_apt_encode(&m, buf, sizeof(buf)), 6);
	assert_memory_equal(buf, want, 6);
}

/* MOVE_ABSOLUTE to 0x00012345 counts: 53 04 06 00 D0 01 01 00 45 23 01 00. */
static void test_apt_long_form_bytes(void **state)
{
	static const uint8_t want[] = { 0x53, 0x04, 0x06, 0x00, 0xD0, 0x01,
					0x01, 0x00, 0x45, 0x23, 0x01, 0x00 };
	struct rig_apt_msg m, back;
	uint8_t buf[32];
	size_t used;
	int32_t pos;

	(void)state;
	rig_apt_move_absolute(&m, 0x12345);
	assert_int_equal(rig_apt_encode(&m, buf, sizeof(buf)), 12);
	assert_memory_equal(buf, want, 12);
	assert_int_equal(rig_apt_decode(buf, 12, &back, &used), RIG_OK);
	assert_int_equal(used, 12);
	assert_int_equal(back.id, RIG_APT_MOT_MOVE_ABSOLUTE);
	assert_int_equal(back.dest, RIG_APT_USB_UNIT);
	back.id = RIG_APT_MOT_GET_POSCOUNTER;	/* same layout */
	assert_int_equal(rig_apt_position(&back, &pos), RIG_OK);
	assert_int_equal(pos, 0x12345);
}

static void test_apt_negative_position(void **state)
{
	struct rig_apt_msg m;
	int32_t pos;

	(void)state;
	rig_apt_move_absolute(&m, -136533);
	m.id = RIG_APT_MOT_GET_POSCOUNTER;
	assert_int_equal(rig_apt_position(&m, &pos), RIG_OK);
	assert_int_equal(pos, -136533);
}

static void test_apt_partial_needs_more(void **state)
{
	struct rig_apt_msg m;
	uint8_t buf[32];
	size_t n, k, used;

	(void)state;
	rig_apt_move_absolute(&m, 99);
	n = rig_apt_encode(&m, buf, sizeof(buf));
	for (k = 0; k < n; k++)
		assert_int_equal(rig_apt_decode(buf, k, &m, &used),
				 RIG_EAGAIN);
}

static void test_apt_rejects_bad_headers(void **state)
{
	static const uint8_t bad_dest[] = { 0x43, 0x04, 0x01, 0x00, 0x33, 0x01 };
	static const uint8_t bad_src[] = { 0x43, 0x04, 0x01, 0x00, 0x50, 0x77 };
	static const uint8_t too_long[] = { 0x53, 0x04, 0x00, 0x10, 0xD0, 0x01 };
	static const uint8_t zero_len[] = { 0x53, 0x04, 0x00, 0x00, 0xD0, 0x01 };
	struct rig_apt_msg m;
	size_t used;

	(void)state;
	assert_int_equal(rig_apt_decode(bad_dest, 6, &m, &used), RIG_EPROTO);
	assert_int_equal(rig_apt_decode(bad_src, 6, &m, &used), RIG_EPROTO);
	assert_int_equal(rig_apt_decode(too_long, 6, &m, &used), RIG_EPROTO);
	assert_int_equal(rig_apt_decode(zero_len, 6, &m, &used), RIG_EPROTO);
	assert_int_equal(used, 0);
}

static void test_apt_position_needs_status(void **state)
{
	struct rig_apt_msg m;
	int32_t pos;

	(void)state;
	rig_apt_short(&m, RIG_APT_MOT_MOVE_COMPLETED, 1, 0);
	assert_int_equal(rig_apt_position(&m, &pos), RIG_EPROTO);
	rig_apt_short(&m, RIG_APT_MOT_MOVE_HOME, 1, 0);
	assert_int_equal(rig_apt_position(&m, &pos), RIG_EPROTO);
}

static void test_apt_encode_refuses_small_buffer(void **state)
{
	struct rig_apt_msg m;
	uint8_t buf[8];

	(void)state;
	rig_apt_move_absolute(&m, 1);
	assert_int_equal(rig_apt_encode(&m, buf, sizeof(buf)), 0);
	m.data_len = RIG_APT_DATA_MAX + 1;
	assert_int_equal(rig_apt_encode(&m, buf, sizeof(buf)), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_apt_short_form_bytes),
		cmocka_unit_test(test_apt_long_form_bytes),
		cmocka_unit_test(test_apt_negative_position),
		cmocka_unit_test(test_apt_partial_needs_more),
		cmocka_unit_test(test_apt_rejects_bad_headers),
		cmocka_unit_test(test_apt_position_needs_status),
		cmocka_unit_test(test_apt_encode_refuses_small_buffer),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
