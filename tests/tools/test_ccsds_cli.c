/*
 * test_ccsds_cli.c - issue 30 from the command line: `stray ccsds check`
 * shows a file as the toolkit reads it, and `stray availability` flies
 * the OEM and AEM that missions write (an orbit in ITRF, lower-case
 * values and OEM 3.0 header keywords, an AEM 2.0 of Euler angles,
 * re-issued overlapping segments) to the same verdict as the EME2000
 * quaternion files they were made from.  Each was refused before.
 *
 * STRAY_BIN=/path/to/old/stray runs the same probes against another build.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/stat.h>
#include <cmocka.h>
#include <cJSON.h>
#include <erfa.h>

#include "cli_fixture.h"

#define CURVE "tests/vectors/fdrfw_curve.csv"
#define VEC "tests/vectors/ccsds/"
#define R2D (180.0 / 3.14159265358979323846)

static char heads[128], d_oem[128], d_aem[128];
static cJSON *base;		/* the demo mission flown as written */

static cJSON *fly(const char *oem, const char *aem)
{
	cJSON *j;

	STRAY("--json", "availability", "--oem", (char *)oem, "--aem",
	      (char *)aem, "--heads", heads);
	if (r.status != 0)
		fail_msg("status %d: %s", r.status, r.err);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	return j;
}

/* The same mission: the same epochs, albedo and availability. */
static void same_as_base(cJSON *j)
{
	const cJSON *h0 = cJSON_GetArrayItem(cJSON_GetObjectItem(base, "heads"), 0);
	const cJSON *h1 = cJSON_GetArrayItem(cJSON_GetObjectItem(j, "heads"), 0);

	assert_true(num(j, "epochs") == num(base, "epochs"));
	assert_true(fabs(num(j, "mean_earth_albedo") -
			 num(base, "mean_earth_albedo")) < 1e-6);
	assert_true(fabs(num(h1, "available_frac") - num(h0, "available_frac")) < 1e-9);
	assert_true(fabs(num(h1, "earth_excluded_frac") -
			 num(h0, "earth_excluded_frac")) < 1e-9);
	cJSON_Delete(j);
}

static int setup(void **state)
{
	(void)state;
	if (cli_setup("ccli"))
		return -1;
	snprintf(heads, sizeof(heads), "%s/heads.json", dir);
	snprintf(d_oem, sizeof(d_oem), "%s/d.oem", dir);
	snprintf(d_aem, sizeof(d_aem), "%s/d.aem", dir);
	if (STRAY("firmware-table", "--curve", CURVE, "--out-bin",
		  in_dir("t.bin")) != 0)
		return -1;
	{
		FILE *f = fopen(heads, "w");

		fputs("{\"heads\": [{\"name\": \"A\", \"boresight_body\": "
		      "[0, 0.6428, -0.7660], \"up_body\": [1, 0, 0], "
		      "\"table\": \"t.bin\"}]}", f);
		fclose(f);
	}
	if (STRAY("availability", "--write-oem", d_oem, "--write-aem", d_aem,
		  "--hours", "3") != 0)
		return -1;
	base = NULL;
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	cJSON_Delete(base);
	return cli_teardown();
}

/* The demo OEM rewritten in ITRF2014 (ERFA's IAU 2006/2000A, UT1 = UTC,
 * no pole: the reader's assumption without an IERS table), with OEM 3.0
 * header keywords and lower-case values. */
static char *itrf_oem(void)
{
	FILE *in = fopen(d_oem, "r"), *out;
	char line[512], *path = in_dir("itrf.oem");

	assert_non_null(in);
	out = fopen(path, "w");
	while (fgets(line, sizeof(line), in)) {
		int y, mo, d, h, mi;
		double s, x[6], u1, u2, tt1, tt2, tai1, tai2, m[3][3], rf[3], vf[3];

		if (strncmp(line, "CCSDS_OEM_VERS", 14) == 0) {
			fputs("CCSDS_OEM_VERS = 3.0\nCLASSIFICATION = public\n"
			      "MESSAGE_ID = ISSUE-30\n", out);
			continue;
		}
		if (strncmp(line, "CENTER_NAME", 11) == 0) {
			fputs("CENTER_NAME = Earth\n", out);
			continue;
		}
		if (strncmp(line, "REF_FRAME", 9) == 0) {
			fputs("REF_FRAME = ITRF2014\n", out);
			continue;
		}
		if (strncmp(line, "INTERPOLATION =", 15) == 0) {
			fputs("INTERPOLATION = lagrange\n", out);
			continue;
		}
		if (sscanf(line, "%d-%d-%dT%d:%d:%lf %lf %lf %lf %lf %lf %lf",
			   &y, &mo, &d, &h, &mi, &s, &x[0], &x[1], &x[2], &x[3],
			   &x[4], &x[5]) != 12) {
			fputs(line, out);
			continue;
		}
		eraDtf2d("UTC", y, mo, d, h, mi, s, &u1, &u2);
		eraUtctai(u1, u2, &tai1, &tai2);
		eraTaitt(tai1, tai2, &tt1, &tt2);
		eraC2t06a(tt1, tt2, u1, u2, 0.0, 0.0, m);
		eraRxp(m, x, rf);
		eraRxp(m, x + 3, vf);
		/* velocity seen from the turning Earth */
		vf[0] += 7.292115146706979e-5 * rf[1];
		vf[1] -= 7.292115146706979e-5 * rf[0];
		fprintf(out, "%.*s %.6f %.6f %.6f %.9f %.9f %.9f\n", 26, line,
			rf[0], rf[1], rf[2], vf[0], vf[1], vf[2]);
	}
	fclose(in);
	fclose(out);
	return path;
}

/* The demo AEM as version 2.0 Euler angles Z-Y-X (no ATTITUDE_DIR nor
 * QUATERNION_TYPE), the angles from the quaternion's matrix by hand. */
static char *euler_aem(void)
{
	FILE *in = fopen(d_aem, "r"), *out;
	char line[512], *path = in_dir("euler.aem");

	assert_non_null(in);
	out = fopen(path, "w");
	while (fgets(line, sizeof(line), in)) {
		char ep[40];
		double x, y, z, c, m01, m00, m02, m12, m22;

		if (strncmp(line, "CCSDS_AEM_VERS", 14) == 0) {
			fputs("CCSDS_AEM_VERS = 2.0\n", out);
			continue;
		}
		if (strncmp(line, "ATTITUDE_DIR", 12) == 0 ||
		    strncmp(line, "QUATERNION_TYPE", 15) == 0)
			continue;
		if (strncmp(line, "ATTITUDE_TYPE", 13) == 0) {
			fputs("ATTITUDE_TYPE = euler_angle\nEULER_ROT_SEQ = ZYX\n", out);
			continue;
		}
		if (sscanf(line, "%39s %lf %lf %lf %lf", ep, &x, &y, &z, &c) != 5) {
			fputs(line, out);
			continue;
		}
		/* M(q) of 504.0, q_c last; M = R_x(phi) R_y(theta) R_z(psi) */
		m00 = c * c + x * x - y * y - z * z;
		m01 = 2 * (x * y + c * z);
		m02 = 2 * (x * z - c * y);
		m12 = 2 * (y * z + c * x);
		m22 = c * c - x * x - y * y + z * z;
		fprintf(out, "%s %.12f %.12f %.12f\n", ep,
			atan2(m01, m00) * R2D, -asin(m02) * R2D,
			atan2(m12, m22) * R2D);
	}
	fclose(in);
	fclose(out);
	return path;
}

/* An IERS finals table (fixed columns) with a constant UT1 - UTC. */
static char *finals(double dut1)
{
	char *path = in_dir("finals.txt"), line[80], num[16];
	FILE *f = fopen(path, "w");
	int mjd;

	for (mjd = 61200; mjd < 61220; mjd++) {
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
	return path;
}

static void test_missions_files_fly(void **state)
{
	char *itrf;
	cJSON *j, *k0;

	(void)state;
	base = fly(d_oem, d_aem);
	/* an orbit in ITRF from a GNSS receiver: was refused on REF_FRAME */
	itrf = itrf_oem();
	same_as_base(fly(itrf, d_aem));
	/* with an IERS table of UT1 - UTC = 0.5 s the Earth has turned
	 * 0.5 s further: the first state moves ~0.5 x 7.29e-5 x 6928 km */
	STRAY("--json", "ccsds", "check", itrf, "--iers", finals(0.5));
	if (r.status != 0)
		fail_msg("status %d: %s", r.status, r.err);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	STRAY("--json", "ccsds", "check", itrf);
	k0 = cJSON_Parse(r.out);
	assert_non_null(k0);
	{
		const cJSON *a = cJSON_GetObjectItem(cJSON_GetObjectItem(j, "first"), "r_km");
		const cJSON *b = cJSON_GetObjectItem(cJSON_GetObjectItem(k0, "first"), "r_km");
		double d = 0.0;
		int k;

		for (k = 0; k < 3; k++)
			d += pow(cJSON_GetArrayItem(a, k)->valuedouble -
				 cJSON_GetArrayItem(b, k)->valuedouble, 2);
		d = sqrt(d);
		if (!(d > 0.2 && d < 0.26))
			fail_msg("the table moved the first state by %g km", d);
	}
	cJSON_Delete(j);
	cJSON_Delete(k0);
	STRAY("availability", "--oem", itrf, "--aem", d_aem, "--heads", heads,
	      "--iers", in_dir("nope.txt"));
	expect_bad("nope.txt");
	/* attitude as AEM 2.0 Euler angles: was refused on ATTITUDE_TYPE */
	same_as_base(fly(d_oem, euler_aem()));
}

/* The demo AEM re-issued: a second segment repeats the last hour with
 * the same attitude (later wins inside its useable span); was refused
 * as epochs going back. */
static void test_overlapping_segments(void **state)
{
	FILE *in = fopen(d_aem, "r"), *out;
	char line[512], meta[2048] = "", data[1 << 16] = "";
	char *path = in_dir("reissued.aem");
	int in_meta = 0, in_data = 0;

	(void)state;
	assert_non_null(in);
	out = fopen(path, "w");
	while (fgets(line, sizeof(line), in)) {
		if (strncmp(line, "META_START", 10) == 0)
			in_meta = 1;
		if (in_meta && strlen(meta) + strlen(line) < sizeof(meta))
			strcat(meta, line);
		if (strncmp(line, "META_STOP", 9) == 0)
			in_meta = 0;
		if (strncmp(line, "DATA_STOP", 9) == 0)
			in_data = 0;
		/* the last hour, 02:00 on */
		if (in_data && strncmp(line + 11, "02", 2) >= 0 &&
		    strlen(data) + strlen(line) < sizeof(data))
			strcat(data, line);
		if (strncmp(line, "DATA_START", 10) == 0)
			in_data = 1;
		fputs(line, out);
	}
	fprintf(out, "%sDATA_START\n%sDATA_STOP\n", meta, data);
	fclose(in);
	fclose(out);
	STRAY("ccsds", "check", path);
	if (r.status != 0 || !strstr(r.out, "segment 2"))
		fail_msg("status %d: %s%s", r.status, r.out, r.err);
	same_as_base(fly(d_oem, path));
}

static void test_check_prints_what_was_read(void **state)
{
	cJSON *j, *segs;

	(void)state;
	STRAY("ccsds", "check", VEC "oemLowerCaseValue.oem");
	if (r.status != 0)
		fail_msg("status %d: %s", r.status, r.err);
	assert_non_null(strstr(r.out, "CCSDS OEM 1.0"));
	assert_non_null(strstr(r.out, "segment 1"));
	assert_non_null(strstr(r.out, "first 2015-08-27T00:00:00.000000"));
	assert_non_null(strstr(r.out, "last  2015-08-27T00:05:00.000000"));
	STRAY("--json", "ccsds", "check", VEC "AEMExample14.txt");
	if (r.status != 0)
		fail_msg("status %d: %s", r.status, r.err);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	assert_string_equal(cJSON_GetObjectItem(j, "message")->valuestring, "AEM");
	assert_string_equal(cJSON_GetObjectItem(j, "time_system")->valuestring, "TAI");
	segs = cJSON_GetObjectItem(j, "segments");
	assert_int_equal(cJSON_GetArraySize(segs), 5);
	assert_string_equal(cJSON_GetObjectItem(cJSON_GetArrayItem(segs, 1),
						"attitude_type")->valuestring,
			    "SPIN/NUTATION_MOM");
	assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(
		cJSON_GetObjectItem(j, "first"), "q_ib")), 4);
	assert_true(num(j, "holes") >= 1);	/* 18 days between segments */
	cJSON_Delete(j);
	/* an Earth-fixed OEM: said converted */
	STRAY("--json", "ccsds", "check", VEC "OEMExample5ITRF.txt");
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	assert_true(cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetArrayItem(
		cJSON_GetObjectItem(j, "segments"), 0), "converted_to_inertial")));
	cJSON_Delete(j);
	/* a useable span opening inside a gap has no first state: said so,
	 * not printed from memory never written */
	{
		char *g = in_dir("gapstart.oem");
		FILE *f = fopen(g, "w");

		fputs("CCSDS_OEM_VERS = 2.0\nMETA_START\nCENTER_NAME = EARTH\n"
		      "REF_FRAME = EME2000\nTIME_SYSTEM = UTC\nINTERPOLATION = LINEAR\n"
		      "USEABLE_START_TIME = 2026-01-01T00:00:30\nMETA_STOP\n"
		      "2026-01-01T00:00:00 7000 0 0 0 7.5 0\n"
		      "2026-01-01T01:00:00 7000 0 0 0 7.5 0\n"
		      "2026-01-01T01:01:00 7000 0 0 0 7.5 0\n"
		      "2026-01-01T01:02:00 7000 0 0 0 7.5 0\n", f);
		fclose(f);
		STRAY("ccsds", "check", g);
		assert_int_equal(r.status, 0);
		assert_non_null(strstr(r.out, "first none"));
		STRAY("--json", "ccsds", "check", g);
		j = cJSON_Parse(r.out);
		assert_non_null(j);
		assert_null(cJSON_GetObjectItem(j, "first"));
		assert_non_null(cJSON_GetObjectItem(j, "last"));
		cJSON_Delete(j);
	}
	/* refusals: one line naming the file and line, exit 2 */
	STRAY("ccsds", "check", VEC "AEM-inconsistent-direction.txt");
	expect_bad("AEM-inconsistent-direction.txt:14: ATTITUDE_DIR");
	STRAY("ccsds", "check");
	expect_bad("check FILE");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_missions_files_fly),
		cmocka_unit_test(test_overlapping_segments),
		cmocka_unit_test(test_check_prints_what_was_read),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
