/*
 * test_notebook_outputs.c - outputs a notebook reads as they are (issue
 * 32 item 4), from `stray` as a user runs it: `diagnose --json` carries
 * the model curves before and after (the plot's points), and the
 * availability series has the epoch in UTC and each head's flag bits as
 * named columns that agree with its bitmask.  Existing keys and columns
 * stay where they were.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>
#include <cmocka.h>

#include "../scratch.h"
#include "run_cli.h"

static char dir[] = "/tmp/stray_nbout_XXXXXX";
static char path[6][300];
enum { TRUTH, MEAS, TABLE, OEM, AEM, HEADS };

static int setup(void **state)
{
	static const char *const name[6] = { "truth.csv", "m.csv", "t.bin",
		"m.oem", "m.aem", "heads.json" };
	FILE *f;
	int i;

	(void)state;
	if (!mkdtemp(dir))
		return -1;
	for (i = 0; i < 6; i++)
		snprintf(path[i], sizeof(path[i]), "%s/%s", dir, name[i]);
	f = fopen(path[HEADS], "w");
	if (!f)
		return -1;
	fprintf(f, "{\"heads\": [{\"name\": \"A\", \"boresight_body\": "
		"[0, 0.6428, -0.7660], \"up_body\": [1, 0, 0], \"table\": "
		"\"t.bin\"}]}\n");
	return fclose(f);
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

static void run_ok(char *const argv[], struct cli_run *r)
{
	if (run_stray(r, argv) != 0)
		fail_msg("%s %s: %s", argv[1], argv[2], r->err);
}

static void diagnose_json_has_the_curves(void **state)
{
	char *trace[] = { "stray", "trace", "--scene", "ref4", "--set",
		"reflectance=0.08", "--angles", "0:10:5,10:60:2.5", "--rays",
		"40000", "--threads", "2", "--out", path[TRUTH], NULL };
	char *phot[] = { "stray", "photometer", "--truth", path[TRUTH],
		"--out", path[MEAS], NULL };
	char *diag[] = { "stray", "--json", "diagnose", path[MEAS], "--scene",
		"ref4", "--rays", "20000", "--threads", "2", "--causes",
		"reflectance,floor", NULL };
	static const char *const key[5] = { "theta_deg", "measured", "sigma",
					    "model_before", "model_after" };
	static struct cli_run r;
	cJSON *j, *c;
	int k, n;

	(void)state;
	run_ok(trace, &r);
	run_ok(phot, &r);
	run_ok(diag, &r);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	n = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(j, "n"));
	assert_true(n > 10);
	assert_non_null(cJSON_GetObjectItem(j, "rms_before"));	/* kept */
	c = cJSON_GetObjectItem(j, "curves");
	assert_non_null(c);
	for (k = 0; k < 5; k++) {
		cJSON *a = cJSON_GetObjectItem(c, key[k]);

		assert_true(cJSON_IsArray(a));
		assert_int_equal(cJSON_GetArraySize(a), n);
	}
	/* theta strictly increasing; both models positive */
	for (k = 1; k < n; k++)
		assert_true(cJSON_GetArrayItem(cJSON_GetObjectItem(c, "theta_deg"),
			    k)->valuedouble > cJSON_GetArrayItem(cJSON_GetObjectItem(
			    c, "theta_deg"), k - 1)->valuedouble);
	assert_true(cJSON_GetArrayItem(cJSON_GetObjectItem(c, "model_after"),
				       0)->valuedouble > 0.0);
	cJSON_Delete(j);
}

/* Column index of name in the header line h, or -1. */
static int column(const char *h, const char *name)
{
	int k = 0;
	size_t len = strlen(name);

	for (;;) {
		if (strncmp(h, name, len) == 0 && (h[len] == ',' || h[len] == '\n'
						   || h[len] == '\0'))
			return k;
		h = strchr(h, ',');
		if (!h)
			return -1;
		h++;
		k++;
	}
}

/* Field k of a CSV line, copied into buf. */
static const char *field(const char *line, int k, char *buf, size_t size)
{
	size_t n;

	while (k-- > 0 && line)
		line = strchr(line, ',') ? strchr(line, ',') + 1 : NULL;
	assert_non_null(line);
	n = strcspn(line, ",\n");
	if (n >= size)
		n = size - 1;
	memcpy(buf, line, n);
	buf[n] = '\0';
	return buf;
}

static void availability_series_named(void **state)
{
	char csv[300];
	char *tab[] = { "stray", "firmware-table", "--curve",
		"tests/vectors/fdrfw_curve.csv", "--out-bin", path[TABLE], NULL };
	char *gen[] = { "stray", "availability", "--write-oem", path[OEM],
		"--write-aem", path[AEM], "--hours", "1", NULL };
	char *fly[] = { "stray", "availability", "--oem", path[OEM], "--aem",
		path[AEM], "--heads", path[HEADS], "--out", csv, NULL };
	static const char *const bit[8] = { "A_sun_excluded",
		"A_moon_excluded", "A_earth_excluded", "A_sun_in_fov",
		"A_moon_in_fov", "A_earth_in_fov", "A_sun_eclipsed",
		"A_input_invalid" };
	static struct cli_run r;
	static char text[1 << 20];
	char *line, *header, buf[64];
	int col[8], k, rows = 0, eclipsed = 0, cf, ct, cu;
	FILE *f;
	size_t n;

	(void)state;
	snprintf(csv, sizeof(csv), "%s/a.csv", dir);
	run_ok(tab, &r);
	run_ok(gen, &r);
	run_ok(fly, &r);
	f = fopen(csv, "r");
	assert_non_null(f);
	n = fread(text, 1, sizeof(text) - 1, f);
	fclose(f);
	text[n] = '\0';
	header = strchr(text, '\n') + 1;	/* after the '#' line */
	/* the existing columns first, where they were */
	assert_int_equal(strncmp(header, "t_s,albedo,A_flags,A_sun_deg,"
				 "A_false_stars,any_available,", 57), 0);
	cu = column(header, "utc");
	cf = column(header, "A_flags");
	ct = column(header, "t_s");
	assert_int_equal(cu, 6);
	for (k = 0; k < 8; k++) {
		col[k] = column(header, bit[k]);
		assert_int_equal(col[k], 7 + k);
	}
	for (line = strchr(header, '\n') + 1; *line;
	     line = strchr(line, '\n') + 1) {
		unsigned flags = (unsigned)atoi(field(line, cf, buf, sizeof(buf)));
		double t = atof(field(line, ct, buf, sizeof(buf)));
		char want[64];
		int s = (int)t;

		for (k = 0; k < 8; k++)
			assert_int_equal(atoi(field(line, col[k], buf, sizeof(buf))),
					 (int)((flags >> k) & 1u));
		eclipsed += (int)((flags >> 6) & 1u);
		/* the demo mission starts 2026-06-21T00:00:00 UTC */
		snprintf(want, sizeof(want), "2026-06-21T%02d:%02d:%02d.000000Z",
			 s / 3600, s / 60 % 60, s % 60);
		assert_string_equal(field(line, cu, buf, sizeof(buf)), want);
		rows++;
	}
	assert_int_equal(rows, 361);	/* one hour every 10 s */
	assert_true(eclipsed > 0);	/* the bits are not all zero */
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(diagnose_json_has_the_curves),
		cmocka_unit_test(availability_series_named),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
