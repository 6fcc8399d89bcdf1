/*
 * test_ccsds_segments.c - issue 30: OEM segments as the standard means
 * them (useable spans, a later segment wins where spans overlap, holes
 * never interpolated across, each segment interpolated as its metadata
 * say) and covariance blocks checked as Orekit's tests check them.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "stray/aem.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/oem.h"
#include "../test_util.h"

static int parse_oem(const char *text, struct stray_oem *o, char *msg)
{
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_oem_parse(text, strlen(text), "t.oem", o, &err);
	stray_error_format(&err, msg, 512);
	return rc;
}

#define SEG_OEM(useable) "META_START\nCENTER_NAME = EARTH\nREF_FRAME = EME2000\n" \
	"TIME_SYSTEM = UTC\nINTERPOLATION = LAGRANGE\nINTERPOLATION_DEGREE = 1\n" \
	useable "META_STOP\n"

static void test_segments(void **state)
{
	struct stray_oem o;
	char msg[512];
	double t0, r[3], v[3];

	(void)state;
	/* re-issued data: the second segment (x = 8000) overlaps the first
	 * (x = 7000) from 00:02 to 00:04; inside its useable span it wins */
	assert_int_equal(parse_oem("CCSDS_OEM_VERS = 2.0\n" SEG_OEM("")
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:02:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:04:00 7000 0 0 0 7.5 0\n"
		SEG_OEM("USEABLE_START_TIME = 2026-01-01T00:02:00\n"
			"USEABLE_STOP_TIME = 2026-01-01T00:05:00\n")
		"2026-01-01T00:01:00 8000 0 0 0 7.5 0\n"
		"2026-01-01T00:03:00 8000 0 0 0 7.5 0\n"
		"2026-01-01T00:06:00 8000 0 0 0 7.5 0\n", &o, msg), STRAY_OK);
	stray_ccsds_epoch("2026-01-01T00:00:00", STRAY_TS_UTC, &t0);
	assert_int_equal(stray_oem_state(&o, t0 + 90.0, r, v), STRAY_OK);
	assert_near(r[0], 7000.0, 1e-9);	/* first segment's own */
	assert_int_equal(stray_oem_state(&o, t0 + 120.0, r, v), STRAY_OK);
	assert_near(r[0], 8000.0, 1e-9);	/* shared end: the later wins */
	assert_int_equal(stray_oem_state(&o, t0 + 200.0, r, v), STRAY_OK);
	assert_near(r[0], 8000.0, 1e-9);
	assert_int_equal(stray_oem_state(&o, t0 + 300.0, r, v), STRAY_OK);
	assert_near(r[0], 8000.0, 1e-9);
	/* past the second's useable stop, no segment covers */
	assert_int_equal(stray_oem_state(&o, t0 + 330.0, r, v), STRAY_ERANGE);
	assert_near(o.cover.t1 - t0, 300.0, 1e-6);
	assert_int_equal(stray_ccsds_cover_holes(&o.cover, o.t), 0);
	stray_oem_free(&o);
	/* 18 days between two segments: a hole, never interpolated */
	assert_int_equal(parse_oem("CCSDS_OEM_VERS = 2.0\n" SEG_OEM("")
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 7000 0 0 0 7.5 0\n" SEG_OEM("")
		"2026-01-19T00:00:00 7100 0 0 0 7.5 0\n"
		"2026-01-19T00:01:00 7100 0 0 0 7.5 0\n", &o, msg), STRAY_OK);
	assert_int_equal(stray_oem_state(&o, t0 + 9 * 86400.0, r, v), STRAY_ERANGE);
	assert_int_equal(stray_oem_state(&o, t0 + 18 * 86400.0 + 30, r, v), STRAY_OK);
	assert_int_equal(stray_ccsds_cover_holes(&o.cover, o.t), 1);
	stray_oem_free(&o);
	/* contiguous segments without a shared epoch: the minute between
	 * them belongs to neither (each segment is interpolated alone) */
	assert_int_equal(parse_oem("CCSDS_OEM_VERS = 2.0\n" SEG_OEM("")
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 7000 0 0 0 7.5 0\n" SEG_OEM("")
		"2026-01-01T00:02:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:03:00 7000 0 0 0 7.5 0\n", &o, msg), STRAY_OK);
	assert_int_equal(stray_oem_state(&o, t0 + 90.0, r, v), STRAY_ERANGE);
	stray_oem_free(&o);
	/* each segment interpolated as its own metadata say: LINEAR on a
	 * parabola, then LAGRANGE 3, exact on a cubic */
	assert_int_equal(parse_oem("CCSDS_OEM_VERS = 2.0\n"
		"META_START\nCENTER_NAME = EARTH\nREF_FRAME = EME2000\n"
		"TIME_SYSTEM = UTC\nINTERPOLATION = LINEAR\nMETA_STOP\n"
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 7010 0 0 0 7.5 0\n"
		"2026-01-01T00:02:00 7040 0 0 0 7.5 0\n"
		"META_START\nCENTER_NAME = EARTH\nREF_FRAME = EME2000\n"
		"TIME_SYSTEM = UTC\nINTERPOLATION = LAGRANGE\n"
		"INTERPOLATION_DEGREE = 3\nMETA_STOP\n"
		"2026-01-01T00:03:00 7027 0 0 0 7.5 0\n"
		"2026-01-01T00:04:00 7064 0 0 0 7.5 0\n"
		"2026-01-01T00:05:00 7125 0 0 0 7.5 0\n"
		"2026-01-01T00:06:00 7216 0 0 0 7.5 0\n"
		"2026-01-01T00:07:00 7343 0 0 0 7.5 0\n", &o, msg), STRAY_OK);
	assert_int_equal(stray_oem_state(&o, t0 + 30.0, r, v), STRAY_OK);
	assert_near(r[0], 7005.0, 1e-9);	/* linear, not the parabola's 7002.5 */
	assert_int_equal(stray_oem_state(&o, t0 + 210.0, r, v), STRAY_OK);
	assert_near(r[0], 7000.0 + 3.5 * 3.5 * 3.5, 1e-9);
	stray_oem_free(&o);
	/* a useable span outside the segment's records is refused */
	assert_int_equal(parse_oem("CCSDS_OEM_VERS = 2.0\n"
		SEG_OEM("USEABLE_STOP_TIME = 2026-01-01T00:09:00\n")
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 7000 0 0 0 7.5 0\n", &o, msg), STRAY_EPARSE);
	assert_non_null(strstr(msg, "useable span outside"));
	/* START_TIME is an epoch too, in the AEM as in the OEM */
	{
		struct stray_aem a;
		struct stray_error err;
		const char *t = "CCSDS_AEM_VERS = 2.0\nMETA_START\n"
			"START_TIME = 2026-02-30T00:00:00\nREF_FRAME_A = EME2000\n"
			"REF_FRAME_B = SC_BODY_1\nTIME_SYSTEM = UTC\n"
			"ATTITUDE_TYPE = QUATERNION\nMETA_STOP\n";

		stray_error_clear(&err);
		assert_int_equal(stray_aem_parse(t, strlen(t), "t.aem", &a, &err),
				 STRAY_EPARSE);
		assert_int_equal(err.line, 3);
		assert_string_equal(err.column, "START_TIME");
	}
}

/* Orekit's covariance refusals (OEM-too-few/too-many-covariance-
 * columns, -too-large/-too-small-covariance-dimension, -covariance-
 * number-format-error, -keyword-within-covariance), on an Earth orbit. */
static void test_covariance_checked(void **state)
{
	static const struct { const char *block, *needle; } bad[] = {
		{ "1\n0 1\n0 0\n", "row 3 of 2 numbers" },
		{ "1\n0 1\n0 0 1 0\n", "row 3 of 4 numbers" },
		{ "1\n0 1\n0 0 1\n0 0 0 1\n0 0 0 0 1\n0 0 0 0 0 1\n0 0 0 0 0 0 1\n",
		  "a 7th row" },
		{ "1\n0 1\n0 0 1\n0 0 0 1\n0 0 0 0 1\n", "5 of 6 rows" },
		{ "1\n0 1\n0 0 x1\n", "'x1': not a number" },
		{ "USER = 1\n", "keyword inside the covariance block" },
		{ "-1\n0 1\n0 0 1\n0 0 0 1\n0 0 0 0 1\n0 0 0 0 0 1\n", "negative variance" },
		{ "1\n2 1\n0 0 1\n0 0 0 1\n0 0 0 0 1\n0 0 0 0 0 1\n", "correlation beyond 1" },
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		char text[2048], msg[512];
		struct stray_oem o;

		snprintf(text, sizeof(text), "CCSDS_OEM_VERS = 3.0\n"
			 "CLASSIFICATION = public\nMESSAGE_ID = T-1\n" SEG_OEM("")
			 "2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
			 "2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n"
			 "COVARIANCE_START\nEPOCH = 2026-01-01T00:00:00\n"
			 "COV_REF_FRAME = RTN\n%sCOVARIANCE_STOP\n", bad[i].block);
		assert_int_equal(parse_oem(text, &o, msg), STRAY_EPARSE);
		if (!strstr(msg, bad[i].needle) || !strstr(msg, "t.oem:"))
			fail_msg("case %zu: %s", i, msg);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_segments),
		cmocka_unit_test(test_covariance_checked),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
