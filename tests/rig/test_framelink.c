/*
 * test_framelink.c - camera frame link (framelink.c): round trip, every
 * single-bit corruption caught by the CRC32, layout checks on headers,
 * rows and pixel range, command decoding.  The CRC of a known string is
 * checked against the published CRC-32 check value 0xCBF43926.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "rig/bytes.h"
#include "rig/framelink.h"
#include "rig/status.h"

#define NR 3
#define NC 5

static const uint16_t rows[NR] = { 10, 11, 1943 };

static size_t make_frame(uint8_t *buf, size_t cap, struct rig_fl_header *h)
{
	uint16_t px[NR * NC];
	int i;

	for (i = 0; i < NR * NC; i++)
		px[i] = (uint16_t)(i * 271 % 4096);
	memset(h, 0, sizeof(*h));
	h->seq = 77;
	h->exposure_us = 100000;
	h->n_rows = NR;
	h->n_cols = NC;
	h->col0 = 2587;
	h->bits = 12;
	h->payload_len = NR * (2 + 2 * NC);
	return rig_fl_frame_encode(h, rows, px, buf, cap);
}

static void test_fl_crc_is_zlib_crc32(void **state)
{
	(void)state;
	assert_int_equal(crc32(0, (const Bytef *)"123456789", 9), 0xCBF43926u);
}

static void test_fl_round_trip(void **state)
{
	uint8_t buf[256];
	uint16_t r[NR], px[NR * NC];
	struct rig_fl_header h, back;
	size_t n = make_frame(buf, sizeof(buf), &h);

	(void)state;
	assert_int_equal(n, 32 + NR * (2 + 2 * NC) + 4);
	assert_int_equal(rig_fl_frame_decode(buf, n, &back, r, px), RIG_OK);
	assert_int_equal(back.seq, 77);
	assert_memory_equal(r, rows, sizeof(rows));
	assert_int_equal(px[NR * NC - 1], (NR * NC - 1) * 271 % 4096);
	assert_int_equal(rig_fl_frame_decode(buf, n - 1, &back, r, px),
			 RIG_EAGAIN);
}

static void test_fl_every_bit_flip_is_caught(void **state)
{
	uint8_t buf[256];
	struct rig_fl_header h;
	size_t n = make_frame(buf, sizeof(buf), &h), i;
	int bit;

	(void)state;
	for (i = 0; i < n; i++)
		for (bit = 0; bit < 8; bit++) {
			int rc;

			buf[i] ^= (uint8_t)(1 << bit);
			rc = rig_fl_frame_decode(buf, n, &h, NULL, NULL);
			assert_int_not_equal(rc, RIG_OK);
			buf[i] ^= (uint8_t)(1 << bit);
		}
}

/* Re-sign a frame after editing it, so the layout check is what fails. */
static void resign(uint8_t *buf, size_t n)
{
	rig_put_u32(buf + n - 4, (uint32_t)crc32(0, buf, (uInt)(n - 4)));
}

static void test_fl_layout_checks(void **state)
{
	uint8_t buf[256];
	struct rig_fl_header h;
	size_t n = make_frame(buf, sizeof(buf), &h);

	(void)state;
	rig_put_u16(buf + 32 + (2 + 2 * NC), 10);	/* row 2 = row 1 */
	resign(buf, n);
	assert_int_equal(rig_fl_frame_decode(buf, n, &h, NULL, NULL),
			 RIG_EPROTO);
	n = make_frame(buf, sizeof(buf), &h);
	rig_put_u16(buf + 32 + 2, 4096);		/* 13-bit pixel */
	resign(buf, n);
	assert_int_equal(rig_fl_frame_decode(buf, n, &h, NULL, NULL),
			 RIG_EPROTO);
	n = make_frame(buf, sizeof(buf), &h);
	rig_put_u16(buf + 16, 2590);			/* col0 + 5 > 2592 */
	assert_int_equal(rig_fl_header_decode(buf, n, &h), RIG_EPROTO);
	n = make_frame(buf, sizeof(buf), &h);
	rig_put_u32(buf + 24, 1000);			/* payload length */
	assert_int_equal(rig_fl_header_decode(buf, n, &h), RIG_EPROTO);
	n = make_frame(buf, sizeof(buf), &h);
	assert_int_equal(rig_fl_frame_decode(buf, n + 1, &h, NULL, NULL),
			 RIG_EPROTO);			/* trailing byte */
	buf[0] = 'X';
	assert_int_equal(rig_fl_header_decode(buf, n, &h), RIG_EPROTO);
}

static void test_fl_command_round_trip_and_checks(void **state)
{
	struct rig_fl_cmd c, back;
	uint8_t buf[RIG_FL_CMD_LEN];

	(void)state;
	memset(&c, 0, sizeof(c));
	c.opcode = RIG_FL_SET_WINDOW;
	c.n_rows = 2;
	c.rows[0] = 960;
	c.rows[1] = 961;
	c.col0 = 100;
	c.n_cols = 200;
	rig_fl_cmd_encode(&c, buf);
	assert_int_equal(rig_fl_cmd_decode(buf, sizeof(buf), &back), RIG_OK);
	assert_int_equal(back.rows[1], 961);
	assert_int_equal(back.n_cols, 200);
	rig_put_u16(buf + 18, 959);			/* not increasing */
	assert_int_equal(rig_fl_cmd_decode(buf, sizeof(buf), &back),
			 RIG_EPARSE);
	buf[4] = 9;					/* opcode */
	assert_int_equal(rig_fl_cmd_decode(buf, sizeof(buf), &back),
			 RIG_EPARSE);
	assert_int_equal(rig_fl_cmd_decode(buf, 10, &back), RIG_EPARSE);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fl_crc_is_zlib_crc32),
		cmocka_unit_test(test_fl_round_trip),
		cmocka_unit_test(test_fl_every_bit_flip_is_caught),
		cmocka_unit_test(test_fl_layout_checks),
		cmocka_unit_test(test_fl_command_round_trip_and_checks),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
