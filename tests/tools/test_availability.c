/*
 * test_availability.c - `stray availability` as a user runs it: the Sun
 * angle of a head along an OEM/AEM pair against an independent
 * computation (ERFA's time scales and eraEpv00 ephemeris, the AEM
 * quaternion turned into a matrix by CCSDS 504.0's formula written here),
 * the --json keys of issue 15, and the one-line errors for bad files.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>
#include <cmocka.h>
#include <erfa.h>
#include <erfam.h>

#include "../scratch.h"
#include "run_cli.h"

#define CURVE "tests/vectors/fdrfw_curve.csv"
#define N_REC 37	/* 6 h every 600 s */

static char dir[] = "/tmp/stray_avail_XXXXXX";
static char path_oem[256], path_aem[256], path_heads[256], path_csv[256];
static const double axis[3] = { 0.267261241912424, 0.534522483824849,
				0.801783725737273 };	/* (1, 2, 3) / sqrt 14 */
static const double bore_a[3] = { 0.2, -0.3, 0.9327379053 };

static double q_angle(int i)
{
	return 0.3 + 0.05 * i;
}

static void epoch_of(int i, int *h, int *m)
{
	*h = i * 600 / 3600;
	*m = i * 600 % 3600 / 60;
}

static int setup(void **state)
{
	FILE *f;
	int i, h, m;
	char table[300];
	struct cli_run r;

	(void)state;
	if (!mkdtemp(dir))
		return -1;
	snprintf(path_oem, sizeof(path_oem), "%s/o.oem", dir);
	snprintf(path_aem, sizeof(path_aem), "%s/a.aem", dir);
	snprintf(path_heads, sizeof(path_heads), "%s/heads.json", dir);
	snprintf(path_csv, sizeof(path_csv), "%s/t.csv", dir);
	snprintf(table, sizeof(table), "%s/t.bin", dir);
	{
		char *argv[] = { "stray", "firmware-table", "--curve", CURVE,
				 "--out-bin", table, NULL };

		if (run_stray(&r, argv) != 0)
			return -1;
	}
	f = fopen(path_oem, "w");
	fprintf(f, "CCSDS_OEM_VERS = 2.0\nCREATION_DATE = 2026-03-01T00:00:00\n"
		"ORIGINATOR = test\nMETA_START\nOBJECT_NAME = T\nOBJECT_ID = T\n"
		"CENTER_NAME = EARTH\nREF_FRAME = EME2000\nTIME_SYSTEM = UTC\n"
		"INTERPOLATION = LAGRANGE\nINTERPOLATION_DEGREE = 1\nMETA_STOP\n");
	for (i = 0; i < N_REC; i++) {
		double u = 0.001 * i * 600.0, rr = 7000.0;

		epoch_of(i, &h, &m);
		fprintf(f, "2026-03-20T%02d:%02d:00 %.6f %.6f %.6f %.6f %.6f %.6f\n",
			h, m, rr * cos(u), rr * 0.6 * sin(u), rr * 0.8 * sin(u),
			-7.0 * sin(u), 4.2 * cos(u), 5.6 * cos(u));
	}
	fclose(f);
	/* body -> EME2000 (B2A), scalar first: M(q) maps body to inertial */
	f = fopen(path_aem, "w");
	fprintf(f, "CCSDS_AEM_VERS = 1.0\nCREATION_DATE = 2026-03-01T00:00:00\n"
		"ORIGINATOR = test\nMETA_START\nOBJECT_NAME = T\nOBJECT_ID = T\n"
		"REF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\nATTITUDE_DIR = B2A\n"
		"TIME_SYSTEM = UTC\nATTITUDE_TYPE = QUATERNION\n"
		"QUATERNION_TYPE = FIRST\nMETA_STOP\nDATA_START\n");
	for (i = 0; i < N_REC; i++) {
		double a = q_angle(i);

		epoch_of(i, &h, &m);
		fprintf(f, "2026-03-20T%02d:%02d:00 %.15f %.15f %.15f %.15f\n", h,
			m, cos(a / 2), sin(a / 2) * axis[0],
			sin(a / 2) * axis[1], sin(a / 2) * axis[2]);
	}
	fprintf(f, "DATA_STOP\n");
	fclose(f);
	f = fopen(path_heads, "w");
	fprintf(f, "{\"heads\": [{\"name\": \"A\", \"boresight_body\": [%.10f, %.10f, %.10f], "
		"\"table\": \"t.bin\"}, {\"name\": \"B\", \"boresight_body\": [0, 0, -1], "
		"\"up_body\": [0, 1, 0], \"table\": \"t.bin\"}]}\n",
		bore_a[0], bore_a[1], bore_a[2]);
	fclose(f);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

/* M(q) of CCSDS 504.0: (q_c^2 - e.e) I + 2 e e^T - 2 q_c [e x]. */
static void ccsds_dcm(const double q[4], double m[3][3])
{
	const double c = q[0], *e = q + 1;
	double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
	double x[3][3] = { { 0, -e[2], e[1] }, { e[2], 0, -e[0] },
			   { -e[1], e[0], 0 } };
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			m[i][j] = (i == j) * (c * c - ee) + 2 * e[i] * e[j] -
				  2 * c * x[i][j];
}

/* The Sun's angle from head A's boresight at record i, independently. */
static double sun_angle_erfa(int i)
{
	double u1, u2, a1, a2, t1, t2, pvh[2][3], pvb[2][3], sun[3], m[3][3];
	double q[4], b[3], c[3], a = q_angle(i);
	int h, mi, k;

	epoch_of(i, &h, &mi);
	eraDtf2d("UTC", 2026, 3, 20, h, mi, 0.0, &u1, &u2);
	eraUtctai(u1, u2, &a1, &a2);
	eraTaitt(a1, a2, &t1, &t2);
	eraEpv00(t1, t2, pvh, pvb);
	eraSxp(-1.0, pvh[0], sun);
	q[0] = cos(a / 2);
	for (k = 0; k < 3; k++)
		q[k + 1] = sin(a / 2) * axis[k];
	ccsds_dcm(q, m);	/* body -> inertial (B2A) */
	for (k = 0; k < 3; k++)
		b[k] = m[k][0] * bore_a[0] + m[k][1] * bore_a[1] + m[k][2] * bore_a[2];
	eraPxp(b, sun, c);
	return atan2(eraPm(c), eraPdp(b, sun)) * ERFA_DR2D;
}

static void test_sun_angle_against_erfa(void **state)
{
	char *argv[] = { "stray", "availability", "--oem", path_oem, "--aem",
			 path_aem, "--heads", path_heads, "--step-s", "600",
			 "--out", path_csv, NULL };
	struct cli_run r;
	char buf[1 << 16], *line, *save = NULL;
	int rows = 0;
	double worst = 0.0;
	FILE *f;
	size_t n;

	(void)state;
	assert_int_equal(run_stray(&r, argv), 0);
	f = fopen(path_csv, "r");
	assert_non_null(f);
	n = fread(buf, 1, sizeof(buf) - 1, f);
	buf[n] = '\0';
	fclose(f);
	for (line = strtok_r(buf, "\n", &save); line;
	     line = strtok_r(NULL, "\n", &save)) {
		double t, alb, sun;
		unsigned flags;
		int i;

		if (sscanf(line, "%lf,%lf,%u,%lf", &t, &alb, &flags, &sun) != 4)
			continue;
		i = (int)lround(t / 600.0);
		worst = fmax(worst, fabs(sun - sun_angle_erfa(i)));
		assert_true(alb > 0.05 && alb < 0.9);
		rows++;
	}
	assert_int_equal(rows, N_REC);
	/* the module's ephemeris is good to 0.01 deg (test_ephem), the CSV
	 * keeps 0.001 deg */
	if (!(worst < 0.02))
		fail_msg("Sun angle off ERFA by %.4f deg", worst);
}

static void test_json_keys(void **state)
{
	char *argv[] = { "stray", "availability", "--oem", path_oem, "--aem",
			 path_aem, "--heads", path_heads, "--step-s", "60",
			 "--json", NULL };
	static const char *head_keys[] = { "name", "available_frac",
		"sun_excluded_frac", "moon_excluded_frac", "earth_excluded_frac",
		"outages", "longest_outage_s" };
	struct cli_run r;
	cJSON *o, *heads, *h;
	double best = 0.0;
	size_t k;

	(void)state;
	assert_int_equal(run_stray(&r, argv), 0);
	o = cJSON_Parse(r.out);
	assert_non_null(o);
	assert_int_equal(cJSON_GetObjectItem(o, "epochs")->valuedouble, 361);
	assert_int_equal(cJSON_GetObjectItem(o, "span_s")->valuedouble, 21600);
	heads = cJSON_GetObjectItem(o, "heads");
	assert_int_equal(cJSON_GetArraySize(heads), 2);
	cJSON_ArrayForEach(h, heads) {
		for (k = 0; k < sizeof(head_keys) / sizeof(head_keys[0]); k++)
			assert_non_null(cJSON_GetObjectItem(h, head_keys[k]));
		best = fmax(best, cJSON_GetObjectItem(h, "available_frac")->valuedouble);
	}
	assert_string_equal(cJSON_GetObjectItem(cJSON_GetArrayItem(heads, 0), "name")->valuestring, "A");
	/* any head is available at least as often as the best one */
	assert_true(cJSON_GetObjectItem(o, "any_head_available_frac")->valuedouble >= best);
	assert_non_null(cJSON_GetObjectItem(o, "longest_all_out_s"));
	cJSON_Delete(o);
}

static void test_bad_files(void **state)
{
	char bad[300];
	char *argv[] = { "stray", "availability", "--oem", bad, "--aem",
			 path_aem, "--heads", path_heads, NULL };
	char *argv_h[] = { "stray", "availability", "--oem", path_oem, "--aem",
			   path_aem, "--heads", bad, NULL };
	struct cli_run r;
	FILE *f;

	(void)state;
	snprintf(bad, sizeof(bad), "%s/bad.oem", dir);
	f = fopen(bad, "w");
	fprintf(f, "CCSDS_OEM_VERS = 2.0\nMETA_START\nREF_FRAME = MCI\n");
	fclose(f);
	assert_int_equal(run_stray(&r, argv), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "bad.oem:3: REF_FRAME 'MCI'"));
	f = fopen(bad, "w");
	fprintf(f, "{\"heads\": [{\"name\": \"A\", \"table\": \"t.bin\"}]}\n");
	fclose(f);
	assert_int_equal(run_stray(&r, argv_h), 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, "boresight_body"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sun_angle_against_erfa),
		cmocka_unit_test(test_json_keys),
		cmocka_unit_test(test_bad_files),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
