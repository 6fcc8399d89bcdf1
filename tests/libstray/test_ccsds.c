/*
 * test_ccsds.c - the CCSDS OEM and AEM readers (stray/oem.h, stray/aem.h):
 * malformed files refused with line and keyword, interpolation exact on
 * polynomials, the quaternion conventions of 504.0 both ways, SLERP,
 * write/read round trips, the real example files, and the availability
 * statistics and zonal albedo (stray/avail.h) on closed-form cases.
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
#include "../test_util.h"

#define PI_ 3.14159265358979323846

#define OEM_HEAD "CCSDS_OEM_VERS = 2.0\nCREATION_DATE = 2026-01-01T00:00:00\n" \
	"ORIGINATOR = test\nMETA_START\nOBJECT_NAME = SAT\nOBJECT_ID = 1\n"
#define OEM_META_OK "CENTER_NAME = EARTH\nREF_FRAME = EME2000\nTIME_SYSTEM = UTC\n" \
	"INTERPOLATION = LAGRANGE\nINTERPOLATION_DEGREE = 1\nMETA_STOP\n"
#define R1 "2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
#define R2 "2026-01-01T00:01:00 6990 450 0 -0.5 7.4 0\n"

struct bad_case {
	const char *text, *field;
	long line;
};

static const struct bad_case bad_oem[] = {
	{ "", "CCSDS_OEM_VERS", 0 },
	{ "CCSDS_AEM_VERS = 1.0\n", "CCSDS_OEM_VERS", 1 },
	{ "CCSDS_OEM_VERS = 9.0\n", "CCSDS_OEM_VERS", 1 },
	{ OEM_HEAD "CENTER_NAME = MARS\n", "CENTER_NAME", 7 },
	{ OEM_HEAD "REF_FRAME = MCI\n", "REF_FRAME", 7 },
	{ OEM_HEAD "TIME_SYSTEM = MRT\n", "TIME_SYSTEM", 7 },
	{ OEM_HEAD "INTERPOLATION = SPLINE\n", "INTERPOLATION", 7 },
	{ OEM_HEAD "INTERPOLATION_DEGREE = 0\n", "INTERPOLATION_DEGREE", 7 },
	{ OEM_HEAD "COLOUR = RED\n", "COLOUR", 7 },
	{ OEM_HEAD "CENTER_NAME = EARTH\nTIME_SYSTEM = UTC\nMETA_STOP\n", "REF_FRAME", 9 },
	{ OEM_HEAD OEM_META_OK "2026-13-01T00:00:00 7000 0 0 0 7.5 0\n", "epoch", 13 },
	{ OEM_HEAD OEM_META_OK "2026-01-01T00:00:00 7000 0 0 0 7.5\n", "data", 13 },
	{ OEM_HEAD OEM_META_OK "2026-01-01T00:00:00 7000 0 x 0 7.5 0\n", "data", 13 },
	{ OEM_HEAD OEM_META_OK R2 R1, "epoch", 14 },
	{ OEM_HEAD OEM_META_OK R1 "TIME_SYSTEM = TT\n" R2, "TIME_SYSTEM", 14 },
	{ OEM_HEAD OEM_META_OK R1, "data", 13 },
	{ OEM_HEAD "CENTER_NAME = EARTH\n", "META_STOP", 7 },
	{ "CCSDS_OEM_VERS = 2.0\n" R1, "data", 2 },
};

#define AEM_HEAD "CCSDS_AEM_VERS = 1.0\nCREATION_DATE = 2026-01-01T00:00:00\n" \
	"ORIGINATOR = test\nMETA_START\nOBJECT_NAME = SAT\n"
#define AEM_FRAMES "REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\n"
#define AEM_REST "ATTITUDE_DIR = A2B\nTIME_SYSTEM = UTC\nATTITUDE_TYPE = QUATERNION\n" \
	"QUATERNION_TYPE = LAST\nMETA_STOP\n"
#define Q1 "2026-01-01T00:00:00 0 0 0 1\n"
#define Q2 "2026-01-01T00:01:00 0 0 0.70710678 0.70710678\n"

static const struct bad_case bad_aem[] = {
	{ "CCSDS_OEM_VERS = 2.0\n", "CCSDS_AEM_VERS", 1 },
	{ AEM_HEAD "ATTITUDE_DIR = UP\n", "ATTITUDE_DIR", 6 },
	{ AEM_HEAD "QUATERNION_TYPE = MIDDLE\n", "QUATERNION_TYPE", 6 },
	{ AEM_HEAD "ATTITUDE_TYPE = SPIN/WOBBLE\n", "ATTITUDE_TYPE", 6 },
	{ AEM_HEAD "TIME_SYSTEM = TDB\n", "TIME_SYSTEM", 6 },
	{ AEM_HEAD "REF_FRAME_A = SC_BODY_1\nREF_FRAME_B = INSTRUMENT_A\n"
	  AEM_REST, "REF_FRAME_A", 12 },
	{ AEM_HEAD AEM_FRAMES "ATTITUDE_DIR = A2B\nTIME_SYSTEM = UTC\n"
	  "ATTITUDE_TYPE = QUATERNION\nMETA_STOP\n", "QUATERNION_TYPE", 11 },
	{ AEM_HEAD AEM_FRAMES AEM_REST Q1, "data", 13 },
	{ AEM_HEAD AEM_FRAMES AEM_REST "DATA_START\n2026-01-01T00:00:00 0 0 0 2\n", "data", 14 },
	{ AEM_HEAD AEM_FRAMES AEM_REST "DATA_START\n2026-01-01T00:00:00 0 0 1\n", "data", 14 },
	{ AEM_HEAD AEM_FRAMES AEM_REST "DATA_START\n" Q1 Q2, "DATA_STOP", 15 },
	{ AEM_HEAD AEM_FRAMES AEM_REST "DATA_START\n" Q2 Q1 "DATA_STOP\n", "epoch", 15 },
	{ AEM_HEAD AEM_FRAMES AEM_REST "DATA_START\n" Q1 "DATA_STOP\n", "data", 15 },
};

static void test_oem_malformed(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(bad_oem) / sizeof(bad_oem[0]); i++) {
		struct stray_oem o;
		struct stray_error err;
		char msg[512];
		int rc;

		stray_error_clear(&err);
		rc = stray_oem_parse(bad_oem[i].text, strlen(bad_oem[i].text),
				     "bad.oem", &o, &err);
		stray_error_format(&err, msg, sizeof(msg));
		if (rc != STRAY_EPARSE || err.line != bad_oem[i].line ||
		    strcmp(err.column[0] ? err.column : err.field, bad_oem[i].field) != 0)
			fail_msg("case %zu: rc %d, '%s' (want line %ld, %s)", i,
				 rc, msg, bad_oem[i].line, bad_oem[i].field);
		assert_non_null(strstr(msg, "bad.oem"));
		assert_null(strchr(msg, '\n'));
		assert_null(o.t);
	}
}

static void test_aem_malformed(void **state)
{
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(bad_aem) / sizeof(bad_aem[0]); i++) {
		struct stray_aem a;
		struct stray_error err;
		char msg[512];
		int rc;

		stray_error_clear(&err);
		rc = stray_aem_parse(bad_aem[i].text, strlen(bad_aem[i].text),
				     "bad.aem", &a, &err);
		stray_error_format(&err, msg, sizeof(msg));
		if (rc != STRAY_EPARSE || err.line != bad_aem[i].line ||
		    strcmp(err.column[0] ? err.column : err.field, bad_aem[i].field) != 0)
			fail_msg("case %zu: rc %d, '%s' (want line %ld, %s)", i,
				 rc, msg, bad_aem[i].line, bad_aem[i].field);
		assert_null(a.q);
	}
}

/* A polynomial of degree deg in x = (t - t0) / 100, and its derivative
 * in per-second units; scaled to speeds the OEM reader takes as an
 * Earth orbit (under 25 km/s). */
#define P_SCALE 1e-3
static double poly(int c, int deg, double x, double *d)
{
	double p = 0.0, dp = 0.0;
	int k;

	for (k = deg; k >= 0; k--) {
		double a = 0.1 * ((double)((k * 7 + c * 3) % 11) - 5.0 + 0.25 * c);

		dp = dp * x + p;
		p = p * x + a;
	}
	*d = dp / 100.0 * P_SCALE;
	return p * P_SCALE;
}

/* Added to x: the polynomial's orbit above the Earth's surface. */
#define X_OFF 1e4

/* An OEM of records every 60 s of the polynomial, parsed back. */
static void poly_oem(const char *interp, int deg, int pdeg,
		     struct stray_oem *o)
{
	char *buf = malloc(1 << 16), epoch[40];
	struct stray_error err;
	double t0;
	size_t n;
	int i, c;

	assert_int_equal(stray_ccsds_epoch("2026-03-01T00:00:00", STRAY_TS_TT, &t0), 0);
	n = (size_t)snprintf(buf, 1 << 16, "CCSDS_OEM_VERS = 2.0\nMETA_START\n"
		"CENTER_NAME = EARTH\nREF_FRAME = ICRF\nTIME_SYSTEM = TT\n"
		"INTERPOLATION = %s\nINTERPOLATION_DEGREE = %d\nMETA_STOP\n",
		interp, deg);
	for (i = 0; i < 12; i++) {
		double x = i * 0.6, d;

		stray_ccsds_format_epoch(t0 + i * 60.0, STRAY_TS_TT, epoch, sizeof(epoch));
		n += (size_t)snprintf(buf + n, (1 << 16) - n, "%s", epoch);
		for (c = 0; c < 3; c++)
			n += (size_t)snprintf(buf + n, (1 << 16) - n, " %.17g",
					      poly(c, pdeg, x, &d) + (c ? 0.0 : X_OFF));
		for (c = 0; c < 3; c++) {
			poly(c, pdeg, x, &d);
			n += (size_t)snprintf(buf + n, (1 << 16) - n, " %.17g", d);
		}
		n += (size_t)snprintf(buf + n, (1 << 16) - n, "\n");
	}
	stray_error_clear(&err);
	if (stray_oem_parse(buf, n, "poly.oem", o, &err) != STRAY_OK) {
		char msg[512];

		fail_msg("%s", stray_error_format(&err, msg, sizeof(msg)));
	}
	free(buf);
}

/* Largest error of the interpolated state against the polynomial. */
static double poly_error(const struct stray_oem *o, int pdeg, double *verr)
{
	double worst = 0.0, t;
	int c;

	*verr = 0.0;
	for (t = o->t[0]; t <= o->t[o->n - 1]; t += 7.3) {
		double r[3], v[3], d;

		assert_int_equal(stray_oem_state(o, t, r, v), STRAY_OK);
		for (c = 0; c < 3; c++) {
			double p = poly(c, pdeg, (t - o->t[0]) / 100.0, &d) +
				   (c ? 0.0 : X_OFF);

			worst = fmax(worst, fabs(r[c] - p));
			*verr = fmax(*verr, fabs(v[c] - d));
		}
	}
	return worst;
}

static void test_interpolation_exact_on_polynomials(void **state)
{
	struct stray_oem o;
	double ve, e;

	(void)state;
	/* Lagrange of degree 5: exact on a quintic, not on a sextic */
	poly_oem("LAGRANGE", 5, 5, &o);
	assert_true(poly_error(&o, 5, &ve) < 1e-7);
	stray_oem_free(&o);
	poly_oem("LAGRANGE", 5, 6, &o);
	assert_true(poly_error(&o, 6, &ve) > 1e-3 * P_SCALE);
	stray_oem_free(&o);
	/* Hermite of degree 7 (4 records with velocities): exact to degree
	 * 7 in position and its derivative; not on degree 8 */
	poly_oem("HERMITE", 7, 7, &o);
	e = poly_error(&o, 7, &ve);
	assert_true(e < 1e-7);
	assert_true(ve < 1e-9);
	stray_oem_free(&o);
	poly_oem("HERMITE", 7, 8, &o);
	assert_true(poly_error(&o, 8, &ve) > 1e-3 * P_SCALE);
	/* at a record the record itself */
	{
		double r[3], v[3], d;

		assert_int_equal(stray_oem_state(&o, o.t[7], r, v), STRAY_OK);
		assert_near(r[1], poly(1, 8, 7 * 0.6, &d), 1e-7);
		assert_int_equal(stray_oem_state(&o, o.t[0] - 1.0, r, v), STRAY_ERANGE);
	}
	stray_oem_free(&o);
}

/* M(q) of CCSDS 504.0 written out element by element. */
static void dcm_by_hand(const double q[4], double m[3][3])
{
	double c = q[0], x = q[1], y = q[2], z = q[3];

	m[0][0] = c * c + x * x - y * y - z * z;
	m[0][1] = 2 * (x * y + c * z);
	m[0][2] = 2 * (x * z - c * y);
	m[1][0] = 2 * (x * y - c * z);
	m[1][1] = c * c - x * x + y * y - z * z;
	m[1][2] = 2 * (y * z + c * x);
	m[2][0] = 2 * (x * z + c * y);
	m[2][1] = 2 * (y * z - c * x);
	m[2][2] = c * c - x * x - y * y + z * z;
}

static void aem_one(const char *meta, const char *q_text, double q[4])
{
	char buf[2048];
	struct stray_aem a;
	struct stray_error err;
	int n = snprintf(buf, sizeof(buf), "CCSDS_AEM_VERS = 1.0\nMETA_START\n%s"
			 "TIME_SYSTEM = TAI\nATTITUDE_TYPE = QUATERNION\nMETA_STOP\n"
			 "DATA_START\n2026-01-01T00:00:00 %s\n"
			 "2026-01-01T00:00:10 %s\nDATA_STOP\n", meta, q_text, q_text);

	stray_error_clear(&err);
	assert_int_equal(stray_aem_parse(buf, (size_t)n, "q.aem", &a, &err), STRAY_OK);
	assert_int_equal(stray_aem_attitude(&a, a.t[0] + 5.0, q), STRAY_OK);
	stray_aem_free(&a);
}

static void test_quaternion_conventions(void **state)
{
	const double s = sqrt(0.5);
	double q[4], m[3][3], h[3][3], v[3];
	int i, j, k;

	(void)state;
	/* 90 deg about z, EME2000 -> body, A2B, scalar last: the inertial
	 * x axis is the body's -y (504.0: M maps A to B) */
	aem_one("REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\nATTITUDE_DIR = A2B\n"
		"QUATERNION_TYPE = LAST\n", "0 0 0.70710678118654752 0.70710678118654752", q);
	stray_q_dcm(q, m);
	for (k = 0; k < 3; k++)
		v[k] = m[k][0];
	assert_near(v[0], 0.0, 1e-12);
	assert_near(v[1], -1.0, 1e-12);
	assert_near(v[2], 0.0, 1e-12);
	/* the same attitude written every other way gives the same q_ib */
	{
		const char *metas[] = {
			"REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\nATTITUDE_DIR = A2B\nQUATERNION_TYPE = FIRST\n",
			"REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\nATTITUDE_DIR = B2A\nQUATERNION_TYPE = FIRST\n",
			"REF_FRAME_A = SC_BODY_1\nREF_FRAME_B = GCRF\nATTITUDE_DIR = A2B\nQUATERNION_TYPE = FIRST\n",
			"REF_FRAME_A = SC_BODY_1\nREF_FRAME_B = ICRF\nATTITUDE_DIR = B2A\nQUATERNION_TYPE = FIRST\n",
		};
		const char *qs[] = { "0.70710678118654752 0 0 0.70710678118654752",
				     "0.70710678118654752 0 0 -0.70710678118654752",
				     "0.70710678118654752 0 0 -0.70710678118654752",
				     "0.70710678118654752 0 0 0.70710678118654752" };
		for (i = 0; i < 4; i++) {
			double p[4];

			aem_one(metas[i], qs[i], p);
			for (k = 0; k < 4; k++)
				assert_near(p[k], q[k], 1e-12);
		}
	}
	/* M(q) against the formula by hand, and its inverse, on a general q */
	{
		double g[4] = { 0.3, -0.5, 0.7, 0.1 }, n = 0.0, back[4];

		for (k = 0; k < 4; k++)
			n += g[k] * g[k];
		for (k = 0; k < 4; k++)
			g[k] /= sqrt(n);
		stray_q_dcm(g, m);
		dcm_by_hand(g, h);
		for (i = 0; i < 3; i++)
			for (j = 0; j < 3; j++)
				assert_near(m[i][j], h[i][j], 1e-14);
		stray_dcm_q(m, back);
		for (k = 0; k < 4; k++)
			assert_near(back[k], g[k] * (back[0] * g[0] < 0 ? -1 : 1), 1e-12);
	}
	(void)s;
}

static void test_slerp(void **state)
{
	double a[4] = { 1, 0, 0, 0 }, b[4] = { sqrt(0.5), 0, 0, sqrt(0.5) };
	double nb[4] = { -b[0], 0, 0, -b[3] }, q[4], f;

	(void)state;
	for (f = 0.0; f <= 1.0; f += 0.125) {
		stray_q_slerp(a, b, f, q);
		/* constant rate about z: angle f * 90 deg */
		assert_near(q[0], cos(f * PI_ / 4), 1e-12);
		assert_near(q[3], sin(f * PI_ / 4), 1e-12);
		stray_q_slerp(a, nb, f, q);	/* shortest arc */
		assert_near(fabs(q[3]), sin(f * PI_ / 4), 1e-12);
	}
}

static void test_epochs(void **state)
{
	double t, u;
	char buf[40];

	(void)state;
	/* J2000.0 is 2000-01-01T12:00:00 TT = 11:58:55.816 UTC */
	assert_int_equal(stray_ccsds_epoch("2000-01-01T12:00:00", STRAY_TS_TT, &t), 0);
	assert_near(t, 0.0, 1e-9);
	assert_int_equal(stray_ccsds_epoch("2000-01-01T11:58:55.816", STRAY_TS_UTC, &t), 0);
	assert_near(t, 0.0, 1e-6);
	/* the leap second at the end of 2016: 23:59:60 exists */
	assert_int_equal(stray_ccsds_epoch("2016-12-31T23:59:60", STRAY_TS_UTC, &t), 0);
	assert_int_equal(stray_ccsds_epoch("2017-01-01T00:00:00", STRAY_TS_UTC, &u), 0);
	assert_near(u - t, 1.0, 1e-6);
	/* day of year form, TAI */
	assert_int_equal(stray_ccsds_epoch("2017-001T00:00:00Z", STRAY_TS_TAI, &t), 0);
	assert_near(u - t, 37.0, 1e-6);
	stray_ccsds_format_epoch(u + 0.25, STRAY_TS_UTC, buf, sizeof(buf));
	assert_string_equal(buf, "2017-01-01T00:00:00.250000");
	assert_int_equal(stray_ccsds_epoch("2017-02-29T00:00:00", STRAY_TS_UTC, &t), -1);
	assert_int_equal(stray_ccsds_epoch("2017-01-01 00:00:00", STRAY_TS_UTC, &t), -1);
}

static void test_round_trip(void **state)
{
	double t[50], r[50][3], v[50][3], q[50][4], t0;
	struct stray_oem o;
	struct stray_aem a;
	struct stray_error err;
	FILE *f;
	int i, k;

	(void)state;
	stray_ccsds_epoch("2026-06-21T00:00:00", STRAY_TS_UTC, &t0);
	for (i = 0; i < 50; i++) {
		double ang = i * 0.07;

		t[i] = t0 + 30.0 * i + 0.125;
		r[i][0] = 6928.137 * cos(ang);
		r[i][1] = 6928.137 * sin(ang);
		r[i][2] = 10.0 * i;
		v[i][0] = -7.6 * sin(ang);
		v[i][1] = 7.6 * cos(ang);
		v[i][2] = 0.01;
		q[i][0] = cos(ang / 2);
		q[i][1] = 0.0;
		q[i][2] = 0.0;
		q[i][3] = sin(ang / 2);
	}
	f = tmpfile();
	assert_int_equal(stray_oem_write(f, "RT", STRAY_TS_UTC, t,
					 (const double (*)[3])r, (const double (*)[3])v,
					 50, STRAY_INTERP_LAGRANGE, 7), STRAY_OK);
	rewind(f);
	{
		char buf[1 << 14];
		size_t n = fread(buf, 1, sizeof(buf), f);

		stray_error_clear(&err);
		assert_int_equal(stray_oem_parse(buf, n, "rt.oem", &o, &err), STRAY_OK);
	}
	fclose(f);
	assert_int_equal(o.n, 50);
	assert_int_equal(o.interp, STRAY_INTERP_LAGRANGE);
	assert_int_equal(o.degree, 7);
	for (i = 0; i < 50; i++) {
		assert_near(o.t[i], t[i], 1e-6);
		for (k = 0; k < 3; k++) {
			assert_near(o.r[i][k], r[i][k], 1e-6);
			assert_near(o.v[i][k], v[i][k], 1e-9);
		}
	}
	stray_oem_free(&o);
	f = tmpfile();
	assert_int_equal(stray_aem_write(f, "RT", STRAY_TS_UTC, t,
					 (const double (*)[4])q, 50), STRAY_OK);
	rewind(f);
	{
		char buf[1 << 14];
		size_t n = fread(buf, 1, sizeof(buf), f);

		assert_int_equal(stray_aem_parse(buf, n, "rt.aem", &a, &err), STRAY_OK);
	}
	fclose(f);
	assert_int_equal(a.n, 50);
	for (i = 0; i < 50; i++)
		for (k = 0; k < 4; k++)
			assert_near(a.q[i][k], q[i][k], 1e-11);
	stray_aem_free(&a);
}

static void test_real_examples(void **state)
{
	struct stray_oem o;
	struct stray_aem a;
	struct stray_error err;
	double t, r[3], v[3], n;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_oem_read("examples/mission/iss_orekit_oem5.txt", &o, &err), STRAY_OK);
	assert_int_equal(o.n, 49);
	assert_string_equal(o.object_name, "ISS");
	assert_int_equal(o.interp, STRAY_INTERP_HERMITE);
	assert_near(o.r[0][0], 2906.2752178573, 1e-9);
	assert_near(o.v[48][2], -1.2870157271, 1e-12);
	stray_ccsds_epoch("2017-04-11T22:31:43.121856", STRAY_TS_UTC, &t);
	assert_near(o.t[0], t, 1e-6);
	/* halfway between two states 30 min apart the ISS is still on its
	 * orbit (a ~6780 km radius), if not exactly */
	assert_int_equal(stray_oem_state(&o, o.t[0] + 60.0, r, v), STRAY_OK);
	n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	assert_true(n > 6600.0 && n < 6900.0);
	stray_oem_free(&o);
	assert_int_equal(stray_aem_read("examples/mission/mgs_ccsds504_aem.txt", &a, &err), STRAY_OK);
	assert_int_equal(a.n, 8);
	/* QUATERNION_TYPE LAST, A2B from EME2000: q_c is the fourth number */
	assert_near(a.q[0][0], 0.68427 / sqrt(0.56748 * 0.56748 + 0.03146 * 0.03146 +
					       0.45689 * 0.45689 + 0.68427 * 0.68427), 1e-12);
	assert_true(a.q[0][1] > 0.5);
	stray_aem_free(&a);
}

static void test_avail_statistics_closed_form(void **state)
{
	enum { N = 1000, P = 10 };
	uint8_t a[N], b[N], any[N];
	struct stray_avail_stats s;
	int i;

	(void)state;
	/* head a blind by the Sun 3 epochs of every 10, head b by the Earth
	 * 3 of every 10 two epochs earlier: both blind 1 epoch of every 10 */
	for (i = 0; i < N; i++) {
		a[i] = i % P < 3 ? STRAY_AVAIL_SUN : 0;
		b[i] = (i + 2) % P < 3 ? STRAY_AVAIL_EARTH : 0;
		any[i] = a[i] && b[i] ? STRAY_AVAIL_BLIND : 0;
	}
	stray_avail_summarise(a, N, 10.0, &s);
	assert_near(s.available_frac, 0.7, 1e-15);
	assert_near(s.sun_frac, 0.3, 1e-15);
	assert_near(s.earth_frac, 0.0, 0);
	assert_int_equal(s.outages, N / P);
	assert_near(s.longest_outage_s, 30.0, 0);
	assert_near(s.mean_outage_s, 30.0, 1e-12);
	assert_int_equal(s.hist[0], N / P);
	stray_avail_summarise(b, N, 10.0, &s);
	assert_near(s.earth_frac, 0.3, 1e-15);
	/* the first and last runs are cut by the span: 1 and 2 epochs */
	assert_int_equal(s.outages, N / P + 1);
	assert_near(s.longest_outage_s, 30.0, 0);
	stray_avail_summarise(any, N, 10.0, &s);
	assert_near(s.available_frac, 0.9, 1e-15);
	assert_int_equal(s.outages, N / P);
	assert_near(s.longest_outage_s, 10.0, 0);
	/* one long outage of 400 epochs at 10 s: the >= 1 h bin */
	memset(a, 0, sizeof(a));
	memset(a + 100, STRAY_AVAIL_MOON, 400);
	stray_avail_summarise(a, N, 10.0, &s);
	assert_int_equal(s.outages, 1);
	assert_near(s.longest_outage_s, 4000.0, 0);
	assert_int_equal(s.hist[STRAY_AVAIL_BINS - 1], 1);
	assert_near(s.moon_frac, 0.4, 1e-15);
}

static void test_albedo_zonal_mean(void **state)
{
	double dec, x;

	(void)state;
	for (dec = -0.409; dec <= 0.41; dec += 0.2045) {
		double sum = 0.0;
		int k, n = 20000;

		/* area mean: uniform in x = sin(latitude) */
		for (k = 0; k < n; k++) {
			x = -1.0 + (k + 0.5) * 2.0 / n;
			sum += stray_albedo_zonal(asin(x), dec);
		}
		assert_near(sum / n, 0.30, 1e-4);
	}
	/* brighter at the poles than at the equator; the winter pole
	 * brighter than the summer one */
	assert_true(stray_albedo_zonal(1.4, 0.0) > stray_albedo_zonal(0.0, 0.0) + 0.1);
	assert_true(stray_albedo_zonal(1.2, -0.4) > stray_albedo_zonal(1.2, 0.4));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_oem_malformed),
		cmocka_unit_test(test_aem_malformed),
		cmocka_unit_test(test_interpolation_exact_on_polynomials),
		cmocka_unit_test(test_quaternion_conventions),
		cmocka_unit_test(test_slerp),
		cmocka_unit_test(test_epochs),
		cmocka_unit_test(test_round_trip),
		cmocka_unit_test(test_real_examples),
		cmocka_unit_test(test_avail_statistics_closed_form),
		cmocka_unit_test(test_albedo_zonal_mean),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
