/*
 * test_hardening2_ccsds.c - issue 31's probes of the mission inputs of
 * `stray availability` and `stray flightcheck` (CCSDS OEM/AEM, the heads
 * file, epochs): each was accepted, or answered wrongly, before.
 *
 * STRAY_BIN=/path/to/old/stray runs the same probes against another build.
 */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/stat.h>
#include <cmocka.h>
#include <erfa.h>

#include "cli_fixture.h"

#define CURVE "tests/vectors/fdrfw_curve.csv"
#define MAKE_FLIGHT "build/tests/flightcheck/make_flight"

static char heads[128], d_oem[128], d_aem[128];
static char *oem_text, *aem_text;	/* a 6 h demo mission, every 60 s */

static char *slurp_all(const char *path)
{
	FILE *f = fopen(path, "rb");
	char *t = malloc(1 << 22);
	size_t n;

	assert_non_null(f);
	n = fread(t, 1, (1 << 22) - 1, f);
	t[n] = '\0';
	fclose(f);
	return t;
}

/* text with the line starting `prefix` replaced by `with` ("" drops it);
 * every line starting with `prefix` when all is set. */
static char *edit(const char *text, const char *prefix, const char *with,
		  int all)
{
	size_t n = strlen(text), lp = strlen(prefix);
	char *out = malloc(n + strlen(with) * 400 + 1), *o = out;
	const char *p = text;
	int done = 0;

	while (*p) {
		const char *e = strchr(p, '\n');
		size_t len = e ? (size_t)(e - p) + 1 : strlen(p);

		if (strncmp(p, prefix, lp) == 0 && (all || !done)) {
			o += sprintf(o, "%s", with);
			done = 1;
		} else {
			memcpy(o, p, len);
			o += len;
		}
		p += len;
	}
	*o = '\0';
	assert_true(done);
	return out;
}

static void fly(const char *oem, const char *aem)
{
	STRAY("availability", "--oem", (char *)oem, "--aem", (char *)aem,
	      "--heads", heads);
}
static int setup(void **state)
{
	(void)state;
	if (cli_setup("h2c"))
		return -1;
	snprintf(heads, sizeof(heads), "%s/heads.json", dir);
	snprintf(d_oem, sizeof(d_oem), "%s/d.oem", dir);
	snprintf(d_aem, sizeof(d_aem), "%s/d.aem", dir);
	if (STRAY("firmware-table", "--curve", CURVE, "--out-bin",
		  in_dir("t.bin")) != 0)
		return -1;
	put_text("heads.json", "{\"heads\": [{\"name\": \"A\", \"boresight_body\": "
	    "[0, 0.6428, -0.7660], \"up_body\": [1, 0, 0], \"table\": \"t.bin\"}]}");
	if (STRAY("availability", "--write-oem", d_oem, "--write-aem", d_aem,
		  "--hours", "6") != 0)
		return -1;
	oem_text = slurp_all(d_oem);
	aem_text = slurp_all(d_aem);
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	free(oem_text);
	free(aem_text);
	return cli_teardown();
}

/* 1. Writing then flying flies what was just written, in one run (it
 * flew the old files, or failed "No such file" when there were none). */
static void test_write_then_fly(void **state)
{
	char *o = put_text("w.oem", "not an OEM\n"), *a = put_text("w.aem", "old\n");
	char *o2 = in_dir("n.oem"), *a2 = in_dir("n.aem"), *t;

	(void)state;
	STRAY("availability", "--write-oem", o, "--write-aem", a, "--heads",
	      heads, "--hours", "1", "--json");
	if (r.status != 0)
		fail_msg("status %d: %s", r.status, r.err);
	assert_non_null(strstr(r.out, "\"epochs\":\t361"));
	t = slurp_all(o);
	assert_int_equal(strncmp(t, "CCSDS_OEM_VERS", 14), 0);
	free(t);
	/* the one-step form with no files yet */
	STRAY("availability", "--write-oem", o2, "--write-aem", a2, "--heads",
	      heads, "--hours", "1");
	assert_int_equal(r.status, 0);
	assert_true(exists(o2) && exists(a2));
	/* all or nothing: a bad heads file writes neither */
	STRAY("availability", "--write-oem", in_dir("x.oem"), "--write-aem",
	      in_dir("x.aem"), "--heads", put_text("bad.json", "{\"heads\": 1}"));
	expect_bad("bad.json");
	assert_false(exists(in_dir("x.oem")) || exists(in_dir("x.aem")));
}

/* 2. A gap of hours is not interpolated across: the time is reported as
 * not covered and counted in no fraction. */
static void test_gap_not_bridged(void **state)
{
	char *g, *h, *o;

	(void)state;
	/* keep 00:00-00:59 and 05:00-06:00: 4 h 1 min between records,
	 * 1445 epochs of 10 s strictly inside */
	g = edit(oem_text, "2026-06-21T01", "", 1);
	h = edit(g, "2026-06-21T02", "", 1);
	free(g);
	g = edit(h, "2026-06-21T03", "", 1);
	free(h);
	h = edit(g, "2026-06-21T04", "", 1);
	free(g);
	o = put_text("gap.oem", h);
	free(h);
	STRAY("availability", "--oem", o, "--aem", d_aem, "--heads", heads,
	      "--json");
	assert_int_equal(r.status, 0);
	if (!strstr(r.out, "\"not_covered_s\":\t14450") ||
	    !strstr(r.out, "\"covered_epochs\":\t716") ||
	    !strstr(r.out, "\"oem_gaps\":\t1"))
		fail_msg("%s", r.out);
	fly(o, d_aem);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "not covered: 14450 s"));
	/* the same hole in the attitude */
	g = edit(aem_text, "2026-06-21T01", "", 1);
	h = edit(g, "2026-06-21T02", "", 1);
	free(g);
	o = put_text("gap.aem", h);
	free(h);
	STRAY("availability", "--oem", d_oem, "--aem", o, "--heads", heads,
	      "--json");
	assert_int_equal(r.status, 0);
	if (!strstr(r.out, "\"aem_gaps\":\t1") || strstr(r.out, "\"not_covered_s\":\t0,"))
		fail_msg("%s", r.out);
}

/* 3. COVARIANCE_START with no COVARIANCE_STOP swallowed the rest. */
static void test_covariance_unclosed(void **state)
{
	char *t = edit(oem_text, "2026-06-21T00:10:00",
		       "COVARIANCE_START\nEPOCH = 2026-06-21T00:09:00\n"
		       "COV_REF_FRAME = RTN\n1.0\n", 0);

	(void)state;
	fly(put_text("cov.oem", t), d_aem);
	expect_bad("COVARIANCE_STOP");
	assert_non_null(strstr(r.err, "COVARIANCE_START at line 27"));
	free(t);
}

/* 4. Physical checks: a speed of 1e300 km/s, a position at the centre. */
static void test_physical_bounds(void **state)
{
	char *t = edit(oem_text, "2026-06-21T00:10:00",
		       "2026-06-21T00:10:00 7000 0 0 1e300 0 0\n", 0);

	(void)state;
	fly(put_text("v.oem", t), d_aem);
	expect_bad("velocity over 25 km/s");
	free(t);
	t = edit(oem_text, "2026-06-21T00:10:00",
		 "2026-06-21T00:10:00 0 0 0 0 7.5 0\n", 0);
	fly(put_text("r.oem", t), d_aem);
	expect_bad("inside the Earth");
	free(t);
}

/* 5. Second 60 only where a leap second is (ERFA's eraDat says where). */
static void test_leap_seconds(void **state)
{
	double d0, d1;
	char *t;

	(void)state;
	/* 2026-06-21 ends in no leap second; 2016-12-31 does */
	assert_int_equal(eraDat(2026, 6, 21, 0.5, &d0), 0);
	assert_int_equal(eraDat(2026, 6, 22, 0.5, &d1), 0);
	assert_true(d0 == d1);
	t = edit(oem_text, "2026-06-21T00:10:00",
		 "2026-06-21T00:09:60 2906 -6082 0 -0.9 0.4 7.5\n", 0);
	fly(put_text("leap.oem", t), d_aem);
	expect_bad("second 60 where no leap second is");
	free(t);
	assert_int_equal(eraDat(2016, 12, 31, 0.5, &d0), 0);
	assert_int_equal(eraDat(2017, 1, 1, 0.5, &d1), 0);
	assert_true(d1 == d0 + 1.0);
	t = edit(oem_text, "2026-06-21T00:10:00",
		 "2026-06-21T23:59:60 2906 -6082 0 -0.9 0.4 7.5\n", 0);
	fly(put_text("leap2.oem", t), d_aem);
	expect_bad("second 60 where no leap second is");
	free(t);
}

/* 6. Unknown keys in the heads file are named, not passed over. */
static void test_heads_unknown_key(void **state)
{
	(void)state;
	fly(d_oem, d_aem);
	assert_int_equal(r.status, 0);
	STRAY("availability", "--oem", d_oem, "--aem", d_aem, "--heads",
	      put_text("h1.json", "{\"heads\": [{\"name\": \"A\", \"boresight_body\": "
		  "[0, 0, 1], \"up_bdy\": [1, 0, 0], \"table\": \"t.bin\"}]}"));
	expect_bad("'up_bdy'");
	STRAY("availability", "--oem", d_oem, "--aem", d_aem, "--heads",
	      put_text("h2.json", "{\"heads\": [{\"name\": \"A\", \"boresight_body\": "
		  "[0, 0, 1], \"table\": \"t.bin\"}], \"head\": []}"));
	expect_bad("'head'");
}

/* 7. Numbers in KVN are decimal: no hex float, INF or NAN. */
static void test_hex_float(void **state)
{
	char *t = edit(oem_text, "2026-06-21T00:10:00",
		       "2026-06-21T00:10:00 0x1p13 -6082 0 -0.9 0.4 7.5\n", 0);

	(void)state;
	fly(put_text("hex.oem", t), d_aem);
	expect_bad("'0x1p13': not a number");
	free(t);
	t = edit(aem_text, "2026-06-21T00:10:00",
		 "2026-06-21T00:10:00 0x1p-1 0.5 0.5 0.5\n", 0);
	fly(d_oem, put_text("hex.aem", t));
	expect_bad("'0x1p-1': not a number");
	free(t);
}

/* 8. A frame's DATE-OBS outside the AEM is bad input: exit 2, not 1. */
static void test_flightcheck_outside_aem(void **state)
{
	char cmd[600], *late;
	char *aem;

	(void)state;
	snprintf(cmd, sizeof(cmd), "printf 'theta_deg,alpha\\n20,1e-3\\n50,1e-5\\n90,1e-7\\n' > %s/lens.csv && "
		 MAKE_FLIGHT " %s/fr %s/fl.aem %s/lens.csv 1.7 4 0 30 85 >/dev/null",
		 dir, dir, dir, dir);
	assert_int_equal(system(cmd), 0);
	aem = slurp_all(in_dir("fl.aem"));
	late = edit(aem, "2026-06-21T10:00", "", 0);
	free(aem);
	aem = edit(late, "2026-06-21T10:01", "", 0);
	free(late);
	put_text("late.aem", aem);
	free(aem);
	STRAY("flightcheck", in_dir("fr"), "--aem", in_dir("late.aem"),
	      "--model", in_dir("lens.csv"));
	expect_bad("DATE-OBS: outside the AEM's span");
}

/* 9. Outputs that are the same file, or the heads file, are refused
 * before anything is written. */
static void test_outputs_collide(void **state)
{
	char *x = in_dir("same.txt"), *before = slurp_all(heads), *after;

	(void)state;
	STRAY("availability", "--write-oem", x, "--write-aem", x);
	expect_bad("same file");
	assert_false(exists(x));
	STRAY("availability", "--write-oem", heads, "--write-aem",
	      in_dir("y.aem"), "--heads", heads);
	expect_bad("same file");
	after = slurp_all(heads);
	assert_string_equal(before, after);
	assert_false(exists(in_dir("y.aem")));
	free(before);
	free(after);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_write_then_fly),
		cmocka_unit_test(test_gap_not_bridged),
		cmocka_unit_test(test_covariance_unclosed),
		cmocka_unit_test(test_physical_bounds),
		cmocka_unit_test(test_leap_seconds),
		cmocka_unit_test(test_heads_unknown_key),
		cmocka_unit_test(test_hex_float),
		cmocka_unit_test(test_flightcheck_outside_aem),
		cmocka_unit_test(test_outputs_collide),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
