/*
 * test_ccsds_hardening.c - issue 31's rules in the CCSDS readers, at the
 * library: decimal numbers only, second 60 only on leap-second days,
 * a covariance block left open refused, physical bounds on states, the
 * gap rule (interpolation never crosses a step longer than its window),
 * and uncovered epochs counted in no fraction.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "stray/aem.h"
#include "stray/avail.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/oem.h"

#define OEM_HEAD "CCSDS_OEM_VERS = 2.0\nMETA_START\nCENTER_NAME = EARTH\n" \
	"REF_FRAME = EME2000\nTIME_SYSTEM = UTC\n" \
	"INTERPOLATION = LAGRANGE\nINTERPOLATION_DEGREE = 1\nMETA_STOP\n"
#define AEM_HEAD "CCSDS_AEM_VERS = 1.0\nMETA_START\nREF_FRAME_A = EME2000\n" \
	"REF_FRAME_B = SC_BODY_1\nATTITUDE_DIR = A2B\nTIME_SYSTEM = UTC\n" \
	"ATTITUDE_TYPE = QUATERNION\nQUATERNION_TYPE = FIRST\nMETA_STOP\n" \
	"DATA_START\n"

static void test_decimal_numbers(void **state)
{
	static const char *const bad[] = { "0x1p3", "0X10", "inf", "-INF",
		"nan", "1e", "1e+", ".", "+", "1.5x", "1,5", "" };
	static const char *const good[] = { "1", "-1", "+1.5", ".5", "5.",
		"1e3", "1.5E-3", "-0.0e+0" };
	double x;
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
		if (stray_kvn_number(bad[i], &x))
			fail_msg("'%s' taken as %g", bad[i], x);
	for (i = 0; i < sizeof(good) / sizeof(good[0]); i++)
		assert_true(stray_kvn_number(good[i], &x));
	assert_true(stray_kvn_number("1.5E-3", &x) && x == 1.5e-3);
}

static void test_second_60(void **state)
{
	double t, u;

	(void)state;
	/* days that end in a leap second, in UTC only */
	assert_int_equal(stray_ccsds_epoch("2016-12-31T23:59:60.5", STRAY_TS_UTC, &t), 0);
	assert_int_equal(stray_ccsds_epoch("2017-01-01T00:00:00", STRAY_TS_UTC, &u), 0);
	assert_true(fabs(u - t - 0.5) < 1e-6);
	assert_int_equal(stray_ccsds_epoch("1972-06-30T23:59:60", STRAY_TS_UTC, &t), 0);
	assert_int_equal(stray_ccsds_epoch("2015-181T23:59:60", STRAY_TS_UTC, &t), 0);
	/* elsewhere, not */
	assert_int_equal(stray_ccsds_epoch("2026-06-21T23:59:60", STRAY_TS_UTC, &t), -2);
	assert_int_equal(stray_ccsds_epoch("2016-12-31T23:58:60", STRAY_TS_UTC, &t), -2);
	assert_int_equal(stray_ccsds_epoch("2016-12-30T23:59:60", STRAY_TS_UTC, &t), -2);
	assert_int_equal(stray_ccsds_epoch("2016-12-31T23:59:60", STRAY_TS_TAI, &t), -2);
	assert_int_equal(stray_ccsds_epoch("2016-12-31T23:59:60", STRAY_TS_GPS, &t), -2);
	assert_int_equal(stray_ccsds_epoch("2016-12-31T23:59:61", STRAY_TS_UTC, &t), -1);
}

static int oem_rc(const char *text, char *msg, size_t size)
{
	struct stray_oem o;
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_oem_parse(text, strlen(text), "t.oem", &o, &err);
	stray_error_format(&err, msg, size);
	if (rc == STRAY_OK)
		stray_oem_free(&o);
	return rc;
}

static void test_oem_refusals(void **state)
{
	char msg[512];

	(void)state;
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"COVARIANCE_START\nEPOCH = 2026-01-01T00:00:00\n1.0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n"
		"2026-01-01T00:02:00 6970 900 0 -1 7.3 0\n", msg, sizeof(msg)),
		STRAY_EPARSE);
	if (!strstr(msg, "t.oem:13: COVARIANCE_STOP"))
		fail_msg("%s", msg);
	assert_non_null(strstr(msg, "COVARIANCE_START at line 10"));
	/* open to the end of the file */
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n"
		"COVARIANCE_START\nEPOCH = 2026-01-01T00:00:00\n1.0\n", msg,
		sizeof(msg)), STRAY_EPARSE);
	assert_non_null(strstr(msg, "COVARIANCE_STOP"));
	/* closed but short of its 6 rows: refused since issue 30 (it was
	 * skipped unchecked); a whole matrix is read */
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n"
		"COVARIANCE_START\nEPOCH = 2026-01-01T00:00:00\n1.0\n"
		"COVARIANCE_STOP\n", msg, sizeof(msg)), STRAY_EPARSE);
	assert_non_null(strstr(msg, "1 of 6 rows"));
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n"
		"COVARIANCE_START\nEPOCH = 2026-01-01T00:00:00\n1\n0 1\n0 0 1\n"
		"0 0 0 1\n0 0 0 0 1\n0 0 0 0 0 1\nCOVARIANCE_STOP\n", msg,
		sizeof(msg)), STRAY_OK);
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 0 0 0 0 7.5 0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n", msg, sizeof(msg)),
		STRAY_EPARSE);
	assert_non_null(strstr(msg, "inside the Earth"));
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 7000 0 0 1e300 7.5 0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n", msg, sizeof(msg)),
		STRAY_EPARSE);
	assert_non_null(strstr(msg, "velocity over 25 km/s"));
	assert_int_equal(oem_rc(OEM_HEAD
		"2026-01-01T00:00:00 7000 0 0 0x1p3 7.5 0\n"
		"2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n", msg, sizeof(msg)),
		STRAY_EPARSE);
	assert_non_null(strstr(msg, "'0x1p3': not a number"));
}

/* Records every 60 s from 00:00 to 00:10, then from 13:00 to 13:10. */
static void gap_oem(struct stray_oem *o)
{
	char *buf = malloc(1 << 14);
	struct stray_error err;
	size_t n = (size_t)sprintf(buf, "%s", OEM_HEAD);
	int i;

	for (i = 0; i < 22; i++) {
		int h = i < 11 ? 0 : 13, m = i < 11 ? i : i - 11;

		n += (size_t)sprintf(buf + n, "2026-01-01T%02d:%02d:00 %.3f 0 0 1 7.5 0\n",
				     h, m, 7000.0 + 60.0 * (i < 11 ? i : i + 769));
	}
	stray_error_clear(&err);
	assert_int_equal(stray_oem_parse(buf, n, "gap.oem", o, &err), STRAY_OK);
	free(buf);
}

static void test_gap_rule(void **state)
{
	struct stray_oem o;
	double r[3], v[3], t0;

	(void)state;
	gap_oem(&o);
	t0 = o.t[0];
	assert_true(o.gap_s == 120.0);	/* linear: 2 steps of 60 s */
	assert_int_equal(stray_ccsds_gaps(o.t, o.n, o.gap_s), 1);
	/* on either side: the line through that side's records */
	assert_int_equal(stray_oem_state(&o, t0 + 330.0, r, v), STRAY_OK);
	assert_true(fabs(r[0] - 7330.0) < 1e-9);
	assert_int_equal(stray_oem_state(&o, o.t[11] + 30.0, r, v), STRAY_OK);
	assert_true(fabs(r[0] - (7000.0 + 60.0 * 780 + 30.0)) < 1e-9);
	/* at the gap's edges, the records; inside, nothing */
	assert_int_equal(stray_oem_state(&o, o.t[10], r, v), STRAY_OK);
	assert_true(r[0] == 7600.0);
	assert_int_equal(stray_oem_state(&o, o.t[11], r, v), STRAY_OK);
	assert_int_equal(stray_oem_state(&o, o.t[10] + 1.0, r, v), STRAY_ERANGE);
	assert_int_equal(stray_oem_state(&o, t0 + 6.5 * 3600.0, r, v), STRAY_ERANGE);
	/* a missing record (2 steps) is no gap */
	{
		double t[5] = { 0, 60, 180, 240, 300 };
		size_t lo, hi;

		assert_true(stray_ccsds_gap_s(t, 5, 2) == 120.0);
		assert_int_equal(stray_ccsds_piece(t, 5, 120.0, 100.0, 1, &lo, &hi), 0);
		assert_true(lo == 0 && hi == 3);
	}
	stray_oem_free(&o);
}

static void test_aem_gap(void **state)
{
	struct stray_aem a;
	struct stray_error err;
	static const char text[] = AEM_HEAD
		"2026-01-01T00:00:00 1 0 0 0\n2026-01-01T00:01:00 1 0 0 0\n"
		"2026-01-01T00:02:00 1 0 0 0\n2026-01-01T13:00:00 0 1 0 0\n"
		"2026-01-01T13:01:00 0 1 0 0\nDATA_STOP\n";
	double q[4];

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_aem_parse(text, strlen(text), "g.aem", &a, &err), STRAY_OK);
	assert_int_equal(stray_aem_attitude(&a, a.t[1] + 30.0, q), STRAY_OK);
	/* no SLERP through 13 h: half way is no attitude at all */
	assert_int_equal(stray_aem_attitude(&a, 0.5 * (a.t[2] + a.t[3]), q),
			 STRAY_ERANGE);
	assert_int_equal(stray_aem_attitude(&a, a.t[3], q), STRAY_OK);
	assert_true(fabs(q[1]) == 1.0);
	stray_aem_free(&a);
}

static void test_uncovered_in_no_fraction(void **state)
{
	uint8_t m[10] = { 0, STRAY_AVAIL_SUN, STRAY_AVAIL_SUN,
			  STRAY_AVAIL_UNCOVERED, STRAY_AVAIL_UNCOVERED,
			  STRAY_AVAIL_SUN, 0, 0, 0, 0 };
	struct stray_avail_stats s;

	(void)state;
	stray_avail_summarise(m, 10, 10.0, &s);
	assert_int_equal(s.epochs, 8);
	assert_int_equal(s.uncovered, 2);
	assert_true(fabs(s.available_frac - 5.0 / 8.0) < 1e-15);
	assert_true(fabs(s.sun_frac - 3.0 / 8.0) < 1e-15);
	/* the gap ends an outage: 20 s and 10 s, not 50 s */
	assert_int_equal(s.outages, 2);
	assert_true(s.longest_outage_s == 20.0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_decimal_numbers),
		cmocka_unit_test(test_second_60),
		cmocka_unit_test(test_oem_refusals),
		cmocka_unit_test(test_gap_rule),
		cmocka_unit_test(test_aem_gap),
		cmocka_unit_test(test_uncovered_in_no_fraction),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
