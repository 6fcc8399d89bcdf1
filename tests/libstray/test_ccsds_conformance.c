/*
 * test_ccsds_conformance.c - issue 30: the OEM and AEM readers on a
 * peer's published test files (Orekit's, tests/vectors/ccsds/
 * PROVENANCE.md: what Orekit's own tests expect of each), Earth-fixed
 * and of-date frames against ERFA's IAU 2006/2000A path (the library
 * uses 2000B: an independent route), every Euler sequence against the
 * rotation-matrix product it implies (ERFA's eraRx/Ry/Rz), spin
 * (segments and covariance: test_ccsds_segments.c).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <erfa.h>

#include "stray/aem.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/oem.h"
#include "../test_util.h"

#define V "tests/vectors/ccsds/"
#define D2R (M_PI_ / 180.0)
#define M_PI_ 3.14159265358979323846
#define AS2R (M_PI_ / 648000.0)
#define OMEGA 7.292115146706979e-5

/* The refusal of path: STRAY_EPARSE, its line and field (or column). */
static void refused(const char *path, long line, const char *field)
{
	struct stray_oem o;
	struct stray_aem a;
	struct stray_error err;
	char msg[512];
	int rc;

	stray_error_clear(&err);
	rc = strstr(path, "AEM") || strstr(path, "aem") ||
	     strstr(path, "spurious") ?
		stray_aem_read(path, &a, &err) : stray_oem_read(path, &o, &err);
	stray_error_format(&err, msg, sizeof(msg));
	if (rc != STRAY_EPARSE || err.line != line ||
	    strcmp(err.column[0] ? err.column : err.field, field) != 0)
		fail_msg("%s: rc %d, '%s' (want line %ld, %s)", path, rc, msg,
			 line, field);
}

static void read_oem(const char *path, struct stray_oem *o)
{
	struct stray_error err;
	char msg[512];

	stray_error_clear(&err);
	if (stray_oem_read(path, o, &err) != STRAY_OK) {
		stray_error_format(&err, msg, sizeof(msg));
		fail_msg("%s", msg);
	}
}

static void read_aem(const char *path, struct stray_aem *a)
{
	struct stray_error err;
	char msg[512];

	stray_error_clear(&err);
	if (stray_aem_read(path, a, &err) != STRAY_OK) {
		stray_error_format(&err, msg, sizeof(msg));
		fail_msg("%s", msg);
	}
}

static int parse_aem(const char *text, struct stray_aem *a, char *msg)
{
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_aem_parse(text, strlen(text), "t.aem", a, &err);
	stray_error_format(&err, msg, 512);
	return rc;
}

static int parse_oem(const char *text, struct stray_oem *o, char *msg)
{
	struct stray_error err;
	int rc;

	stray_error_clear(&err);
	rc = stray_oem_parse(text, strlen(text), "t.oem", o, &err);
	stray_error_format(&err, msg, 512);
	return rc;
}

/* The angle between two rotations given as matrices [rad]. */
static double angle(const double a[3][3], const double b[3][3])
{
	double tr = 0.0;
	int i, k;

	for (i = 0; i < 3; i++)
		for (k = 0; k < 3; k++)
			tr += a[i][k] * b[i][k];	/* trace(a b^T) */
	tr = (tr - 1.0) / 2.0;
	return acos(tr > 1.0 ? 1.0 : tr < -1.0 ? -1.0 : tr);
}

static void mat_q(const double q[4], double m[3][3])
{
	stray_q_dcm(q, m);
}

/* ---------------------------------------------------------------- OEM */

static void test_orekit_oem(void **state)
{
	struct stray_oem o;
	double t, r[3], v[3];

	(void)state;
	/* OEMExample5: GCRF, HERMITE 1, the ISS over a day (Orekit: 49) */
	read_oem(V "OEMExample5.txt", &o);
	assert_int_equal(o.n, 49);
	assert_string_equal(o.object_name, "ISS");
	assert_near(o.r[0][0], 2906.2752178573, 1e-9);
	stray_oem_free(&o);
	/* lower-case values: CENTER_NAME = Earth, INTERPOLATION = Lagrange
	 * (Orekit: the Earth) */
	read_oem(V "oemLowerCaseValue.oem", &o);
	assert_int_equal(o.interp, STRAY_INTERP_LAGRANGE);
	stray_oem_free(&o);
	/* the ISS ephemeris format, CENTER_NAME = Earth */
	read_oem(V "ISS.resampled.truncated.txt", &o);
	assert_string_equal(o.object_name, "ISS");
	assert_int_equal(o.n, 25);	/* Orekit: 25 coordinates */
	assert_int_equal(stray_oem_state(&o, o.cover.t0 + 100.0, r, v), STRAY_OK);
	stray_oem_free(&o);
	/* TOD with a covariance block (Orekit: one segment, 1 covariance) */
	read_oem(V "test_cov.oem", &o);
	assert_int_equal(o.cover.n_seg, 1);
	assert_int_equal(o.cover.seg[0].n_cov, 1);
	assert_int_equal(o.cover.seg[0].frame, STRAY_FRAME_TOD);
	stray_ccsds_epoch("2019-09-09T00:00:00", STRAY_TS_UTC, &t);
	assert_near(o.t[0], t, 1e-6);
	stray_oem_free(&o);
	/* OEM 3.0 with CLASSIFICATION: the header is read, the Mars
	 * barycentre refused on its line (it was refused on CLASSIFICATION) */
	refused(V "OEMExample1.txt", 10, "CENTER_NAME");
}

/* The ITRF2014 file Orekit wrote from OEMExample5's orbit ("simple
 * EOP": Orekit's test data hold no Earth orientation for 2017, so its
 * UT1 - UTC and pole were zero): converted with zero EOP it lands on the
 * GCRF file within 1 m and 1 mm/s. */
static double itrf_vs_gcrf(const struct stray_oem *g, double *dv)
{
	struct stray_oem f;
	double worst = 0.0;
	size_t i;
	int k;

	read_oem(V "OEMExample5ITRF.txt", &f);
	assert_int_equal(f.n, g->n);
	*dv = 0.0;
	for (i = 0; i < f.n; i++) {
		double d = 0.0, e = 0.0;

		assert_near(f.t[i], g->t[i], 1e-6);
		for (k = 0; k < 3; k++) {
			d += pow(f.r[i][k] - g->r[i][k], 2);
			e += pow(f.v[i][k] - g->v[i][k], 2);
		}
		worst = fmax(worst, sqrt(d));
		*dv = fmax(*dv, sqrt(e));
	}
	stray_oem_free(&f);
	return worst;
}

static void eop_file(const char *path, double dut1)
{
	FILE *f = fopen(path, "w");
	char line[80], num[16];
	int mjd;

	assert_non_null(f);
	/* finals2000A columns: MJD 8-15, x_p 19-27, y_p 38-46, UT1-UTC 59-68 */
	for (mjd = 57850; mjd < 57860; mjd++) {
		memset(line, ' ', 78);
		line[78] = '\0';
		snprintf(num, sizeof(num), "%8.2f", (double)mjd);
		memcpy(line + 7, num, 8);
		snprintf(num, sizeof(num), "%9.6f", 0.0);
		memcpy(line + 18, num, 9);
		memcpy(line + 37, num, 9);
		snprintf(num, sizeof(num), "%10.7f", dut1);
		memcpy(line + 58, num, 10);
		fprintf(f, "%s\n", line);
	}
	fclose(f);
}

static void test_itrf_file_vs_gcrf(void **state)
{
	struct stray_oem g;
	struct stray_error err;
	char path[64];
	double d, dv;

	(void)state;
	read_oem(V "OEMExample5.txt", &g);
	d = itrf_vs_gcrf(&g, &dv);
	print_message("ITRF2014 -> GCRF vs Orekit's GCRF: %.3f m, %.3f mm/s\n",
		      d * 1e3, dv * 1e6);
	assert_true(d < 1e-3 && dv < 1e-6);
	/* an IERS table with UT1 - UTC = 0.4 s turns the Earth 0.4 s
	 * further: 0.4 x 7.29e-5 rad/s x |r_xy| (at most 6800 km), the size
	 * of the error docs/availability.md gives for a missing table */
	snprintf(path, sizeof(path), "/tmp/stray_eop_%d.txt", (int)getpid());
	eop_file(path, 0.4);
	stray_error_clear(&err);
	assert_int_equal(stray_ccsds_eop_load(path, &err), STRAY_OK);
	d = itrf_vs_gcrf(&g, &dv);
	stray_ccsds_eop_clear();
	unlink(path);
	assert_true(d > 0.15 && d < 0.4 * OMEGA * 6800.0 * 1.001);
	stray_oem_free(&g);
}

/* ERFA's 2006/2000A matrix GCRS -> frame and its rate, in the test. */
static void frame_06a(int frame, double t_tt, double m[3][3], int *spins)
{
	double tt2 = t_tt / 86400.0, u1, u2;

	eraTaiutc(2451545.0, tt2 - 32.184 / 86400.0, &u1, &u2);
	*spins = 0;
	switch (frame) {
	case STRAY_FRAME_MOD: eraPmat06(2451545.0, tt2, m); break;
	case STRAY_FRAME_TOD: eraPnm06a(2451545.0, tt2, m); break;
	case STRAY_FRAME_TEME:
		eraPnm06a(2451545.0, tt2, m);
		eraRz(eraGst06a(u1, u2, 2451545.0, tt2) -
		      eraGmst06(u1, u2, 2451545.0, tt2), m);
		break;
	case STRAY_FRAME_GTOD:
		eraPnm06a(2451545.0, tt2, m);
		eraRz(eraGst06a(u1, u2, 2451545.0, tt2), m);
		*spins = 1;
		break;
	default:
		eraC2t06a(2451545.0, tt2, u1, u2, 0.0, 0.0, m);
		*spins = 1;
	}
}

static void test_frames_vs_erfa(void **state)
{
	static const char *const names[] = { "MOD", "TOD", "TEME", "GTOD",
					      "ITRF2014", "ITRF-93" };
	static const int frames[] = { STRAY_FRAME_MOD, STRAY_FRAME_TOD,
		STRAY_FRAME_TEME, STRAY_FRAME_GTOD, STRAY_FRAME_ITRF,
		STRAY_FRAME_ITRF };
	const double ri[3] = { 4000.0, -5200.0, 2300.0 };
	const double vi[3] = { 5.1, 2.9, -4.6 };
	size_t f;

	(void)state;
	/* 2026, and 2031: past ERFA 2.0's "dubious year" (2028), whose
	 * status 1 once dropped the 37 s of TAI - UTC from UT1 (2.7 km) */
	for (f = 0; f < 12; f++) {
		char text[2048], msg[512], e[2][40];
		double m[3][3], rf[2][3], vf[2][3], t[2];
		struct stray_oem o;
		int i, j, spins;

		stray_ccsds_epoch(f < 6 ? "2026-03-20T06:00:00" :
				  "2031-07-02T18:00:00", STRAY_TS_UTC, &t[0]);
		t[1] = t[0] + 60.0;
		for (i = 0; i < 2; i++) {
			double w[3];

			frame_06a(frames[f % 6], t[i], m, &spins);
			eraRxp(m, (double *)ri, rf[i]);
			eraRxp(m, (double *)vi, vf[i]);
			/* seen from turning axes: v - omega x r */
			w[0] = -OMEGA * rf[i][1] * spins;
			w[1] = OMEGA * rf[i][0] * spins;
			w[2] = 0.0;
			for (j = 0; j < 3; j++)
				vf[i][j] -= w[j];
			stray_ccsds_format_epoch(t[i], STRAY_TS_UTC, e[i], 40);
		}
		snprintf(text, sizeof(text), "CCSDS_OEM_VERS = 2.0\nMETA_START\n"
			 "CENTER_NAME = EARTH\nREF_FRAME = %s\nTIME_SYSTEM = UTC\n"
			 "META_STOP\n%s %.9f %.9f %.9f %.12f %.12f %.12f\n"
			 "%s %.9f %.9f %.9f %.12f %.12f %.12f\n", names[f % 6],
			 e[0], rf[0][0], rf[0][1], rf[0][2], vf[0][0], vf[0][1], vf[0][2],
			 e[1], rf[1][0], rf[1][1], rf[1][2], vf[1][0], vf[1][1], vf[1][2]);
		if (parse_oem(text, &o, msg) != STRAY_OK)
			fail_msg("%s: %s", names[f % 6], msg);
		/* 1 m, 1 mm/s: the 2000B model is within 1 mas of 2000A */
		for (i = 0; i < 2; i++)
			for (j = 0; j < 3; j++) {
				assert_near(o.r[i][j], ri[j], 1e-3);
				assert_near(o.v[i][j], vi[j], 1e-6);
			}
		stray_oem_free(&o);
	}
}

/* The readers' grid of precession-nutation against the direct 2000B
 * product, forwards, backwards and across nodes: within 0.01 mas. */
static void test_frame_grid(void **state)
{
	struct stray_ccsds_frame_cache c;
	int f, i;

	(void)state;
	memset(&c, 0, sizeof(c));
	for (f = STRAY_FRAME_ITRF; f <= STRAY_FRAME_TEME; f++)
		for (i = 0; i < 400; i++) {
			/* 2026-03-20 on, 7.3 s steps, a jump back every 50 */
			double t = 8.269e8 + 7.3 * i - (i % 50 == 49 ? 5e4 : 0.0);
			double a[3][3], b[3][3], w[3], d = 0.0;
			int k;

			stray_ccsds_frame_dcm(f, t, a, w);
			stray_ccsds_frame_dcm_cached(&c, f, t, b, w);
			/* elements, not acos: that is blind under ~4 mas */
			for (k = 0; k < 9; k++)
				d = fmax(d, fabs(a[k / 3][k % 3] - b[k / 3][k % 3]));
			if (d > 0.01e-3 * AS2R)
				fail_msg("frame %d at %.1f: %g mas", f, t,
					 d / AS2R * 1e3);
		}
}

/* ---------------------------------------------------------------- AEM */

/* M(q_raw) R(t): what the reader must hold for an attitude against a
 * celestial frame that is not inertial. */
static void expect_q(const struct stray_aem *a, size_t rec,
		     const double raw_q[4], int frame)
{
	double m[3][3], r[3][3], want[3][3], got[3][3];
	int spins;

	mat_q(raw_q, m);
	frame_06a(frame, a->t[rec], r, &spins);
	eraRxr(m, r, want);
	mat_q(a->q[rec], got);
	if (angle(want, got) > AS2R)
		fail_msg("record %zu: %.3f arcsec off", rec,
			 angle(want, got) / AS2R);
}

static void test_orekit_aem(void **state)
{
	struct stray_aem a;
	double t, q[4], m[3][3], want[3][3];
	/* Orekit testIssue739/739_2: the attitude against GTOD / ITRF-93 at
	 * 1996-11-28T22:08:03.555 is (0.74533; 0.42319, -0.45697, 0.23784) */
	const double orekit_q[4] = { 0.74533, 0.42319, -0.45697, 0.23784 };
	double n = 0.0;
	int k;

	(void)state;
	for (k = 0; k < 4; k++)
		n += orekit_q[k] * orekit_q[k];
	read_aem(V "AEMExample08.txt", &a);	/* GTOD, B2A, body is A */
	{
		double u[4];

		for (k = 0; k < 4; k++)
			u[k] = orekit_q[k] / sqrt(n);
		expect_q(&a, 1, u, STRAY_FRAME_GTOD);
		stray_aem_free(&a);
		read_aem(V "AEMExample09.txt", &a);	/* ITRF-93, QUATERNION/RATE */
		expect_q(&a, 1, u, STRAY_FRAME_ITRF);
	}
	/* the useable span starts at 22:08:02.5555: the record of 21:29 is
	 * read for interpolation, not flown */
	stray_ccsds_epoch("1996-11-28T21:29:07.255", STRAY_TS_UTC, &t);
	assert_int_equal(stray_aem_attitude(&a, t, q), STRAY_ERANGE);
	stray_ccsds_epoch("1996-11-28T22:08:02.5555", STRAY_TS_UTC, &t);
	assert_near(a.cover.t0, t, 1e-6);
	stray_aem_free(&a);
	/* Euler 2-3-1 against ITRF-93, first record 0.04 0.05 0.06 deg */
	read_aem(V "AEMExample12.txt", &a);
	{
		double e[3][3];
		int spins;

		eraIr(e);
		eraRy(0.04 * D2R, e);
		eraRz(0.05 * D2R, e);
		eraRx(0.06 * D2R, e);
		frame_06a(STRAY_FRAME_ITRF, a.t[1], m, &spins);
		eraRxr(e, m, want);
		mat_q(a.q[1], m);
		assert_true(angle(want, m) < AS2R);
	}
	stray_aem_free(&a);
	/* v1 QUATERNION/DERIVATIVE, QUATERNION_TYPE FIRST: q as written */
	read_aem(V "AEMExample04.txt", &a);
	assert_int_equal(a.n, 13);
	stray_aem_free(&a);
	/* SPIN (Orekit: 8 records): body z on the spin axis */
	read_aem(V "AEMExample03.txt", &a);
	assert_int_equal(a.n, 8);
	{
		double alpha = 2.6862511e+002 * D2R, delta = 6.8448486e+001 * D2R;
		double zb[3] = { cos(alpha) * cos(delta), sin(alpha) * cos(delta),
				 sin(delta) };

		mat_q(a.q[0], m);
		/* the body z axis in inertial coordinates is M's third row */
		for (k = 0; k < 3; k++)
			assert_near(m[2][k], zb[k], 1e-9);
	}
	stray_aem_free(&a);
	read_aem(V "AEMExample06b.txt", &a);	/* SPIN/NUTATION_MOM */
	assert_int_equal(a.n, 8);
	stray_aem_free(&a);
	/* AEM 2.0, five segments of five types (Orekit testParseAEM04) */
	read_aem(V "AEMExample14.txt", &a);
	assert_int_equal(a.cover.n_seg, 5);
	assert_int_equal(a.cover.seg[0].n, 10);
	assert_string_equal(a.cover.seg[0].kind, "EULER_ANGLE/DERIVATIVE");
	assert_string_equal(a.cover.seg[1].kind, "SPIN/NUTATION_MOM");
	assert_string_equal(a.cover.seg[2].kind, "QUATERNION");
	assert_string_equal(a.cover.seg[3].kind, "QUATERNION/ANGVEL");
	assert_string_equal(a.cover.seg[4].kind, "EULER_ANGLE/ANGVEL");
	assert_int_equal(a.time_system, STRAY_TS_TAI);
	stray_aem_free(&a);
	read_aem(V "AEMExample15.txt", &a);
	stray_aem_free(&a);
	read_aem(V "AEMExample01.txt", &a);
	stray_aem_free(&a);
	read_aem(V "aemLowerCaseValue.aem", &a);
	stray_aem_free(&a);
	/* Orekit's refusals, each on its line */
	refused(V "AEM-inconsistent-direction.txt", 14, "ATTITUDE_DIR");
	refused(V "AEM-inconsistent-quaternion-type.txt", 20, "QUATERNION_TYPE");
	refused(V "AEM-inconsistent-rotation-sequence.txt", 22, "EULER_ROT_SEQ");
	refused(V "AEM-missing-attitude-type.txt", 23, "ATTITUDE_TYPE");
	refused(V "AEM-wrong-keyword.txt", 24, "WRONG_KEYWORD");
	refused(V "AEM-keyword-within-ephemeris.txt", 29, "USER_DEFINED_TEST_KEY");
	refused(V "spurious-metadata.txt", 26, "META_START");
}

static void test_euler_sequences(void **state)
{
	static const char *const seq[12] = { "123", "132", "213", "231",
		"312", "321", "121", "131", "212", "232", "313", "323" };
	static const char *const letters = "XYZ";
	const double ang[3] = { 31.5, -47.25, 122.0 };
	int s, v;

	(void)state;
	for (s = 0; s < 12; s++)
		for (v = 1; v <= 2; v++) {
			char text[1024], msg[512], name[4];
			double want[3][3], got[3][3];
			struct stray_aem a;
			int k;

			for (k = 0; k < 3; k++)	/* v2 letters, v1 digits */
				name[k] = v == 2 ? letters[seq[s][k] - '1'] : seq[s][k];
			name[3] = '\0';
			snprintf(text, sizeof(text), "CCSDS_AEM_VERS = %d.0\nMETA_START\n"
				 "REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\n%s"
				 "TIME_SYSTEM = UTC\nATTITUDE_TYPE = EULER_ANGLE\n"
				 "EULER_ROT_SEQ = %s\nMETA_STOP\nDATA_START\n"
				 "2026-01-01T00:00:00 %g %g %g\n"
				 "2026-01-01T00:00:10 %g %g %g\nDATA_STOP\n", v,
				 v == 1 ? "ATTITUDE_DIR = A2B\n" : "", name,
				 ang[0], ang[1], ang[2], ang[0], ang[1], ang[2]);
			if (parse_aem(text, &a, msg) != STRAY_OK)
				fail_msg("%s: %s", name, msg);
			/* the frame rotations in the sequence's order */
			eraIr(want);
			for (k = 0; k < 3; k++) {
				double x = ang[k] * D2R;

				switch (seq[s][k]) {
				case '1': eraRx(x, want); break;
				case '2': eraRy(x, want); break;
				default: eraRz(x, want); break;
				}
			}
			mat_q(a.q[0], got);
			for (k = 0; k < 9; k++)
				if (fabs(want[k / 3][k % 3] - got[k / 3][k % 3]) > 1e-12)
					fail_msg("%s v%d: M[%d][%d] %.15f, want %.15f",
						 name, v, k / 3, k % 3,
						 got[k / 3][k % 3], want[k / 3][k % 3]);
			stray_aem_free(&a);
		}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_orekit_oem),
		cmocka_unit_test(test_itrf_file_vs_gcrf),
		cmocka_unit_test(test_frames_vs_erfa),
		cmocka_unit_test(test_frame_grid),
		cmocka_unit_test(test_orekit_aem),
		cmocka_unit_test(test_euler_sequences),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
