/*
 * test_frame.c - Bayer read channels (thesis fig. 3.5: 8 channels by
 * row mod 2 and column mod 4) and the frame sanity checks.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

#include "stray/reduce_frame.h"

static void test_bayer_default_layout(void **state)
{
	struct stray_bayer_map m;

	(void)state;
	stray_bayer_default(&m);
	assert_int_equal(stray_bayer_channel(&m, 0, 0), 0);
	assert_int_equal(stray_bayer_channel(&m, 0, 3), 3);
	assert_int_equal(stray_bayer_channel(&m, 1, 0), 4);
	assert_int_equal(stray_bayer_channel(&m, 1, 3), 7);
	/* Period 2 in rows, 4 in columns; ROW0/COL0 phases wrap. */
	assert_int_equal(stray_bayer_channel(&m, 1002, 4001), 1);
	assert_int_equal(stray_bayer_channel(&m, -1, -1), 7);
}

static void test_bayer_parse_custom_and_bad(void **state)
{
	struct stray_bayer_map m;
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_bayer_parse("76543210", &m, &err), STRAY_OK);
	assert_int_equal(stray_bayer_channel(&m, 0, 0), 7);
	assert_int_equal(stray_bayer_channel(&m, 1, 2), 1);
	assert_int_equal(stray_bayer_parse("0123456", &m, &err), STRAY_EPARSE);
	assert_string_equal(err.field, "channels");
	stray_error_clear(&err);
	assert_int_equal(stray_bayer_parse("01234568", &m, &err), STRAY_EPARSE);
	stray_error_clear(&err);
	assert_int_equal(stray_bayer_parse("012345670", &m, &err),
			 STRAY_EPARSE);
}

static void test_frame_check_names_keyword(void **state)
{
	uint16_t pix[4] = { 0 };
	long rows[2] = { 0, 1 };
	struct stray_frame f = { 2, 2, pix, rows, 0, 0.1, 1.0, 1.0, 4095 };
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_frame_check(&f, &err), STRAY_OK);
	f.t_exp_s = 0.0;
	assert_int_equal(stray_frame_check(&f, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "EXPTIME");
	f.t_exp_s = 0.1;
	f.nd_trans = 1.5;
	stray_error_clear(&err);
	assert_int_equal(stray_frame_check(&f, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "NDTRANS");
	f.nd_trans = 1.0;
	f.monitor = NAN;
	stray_error_clear(&err);
	assert_int_equal(stray_frame_check(&f, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "MONITOR");
	f.monitor = 1.0;
	f.sat_level = 0;
	stray_error_clear(&err);
	assert_int_equal(stray_frame_check(&f, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "SATLEVEL");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_bayer_default_layout),
		cmocka_unit_test(test_bayer_parse_custom_and_bad),
		cmocka_unit_test(test_frame_check_names_keyword),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
