/*
 * test_review.c - issue 25's "Done when" for `stray review`: the two
 * example projects (examples/review-cube: five thin vanes, its own
 * sensor, an ideal lens, a 500 km LTAN 10:30 nadir mission with two
 * heads; examples/review-navcam: three vanes with upper bevels, another
 * sensor, a lens curve, a measured curve to diagnose, a 700 km 51.6 deg
 * inertial mission) reviewed with few rays:
 *   - each verdict is the number `stray exclusion` / `stray availability`
 *     print when run by hand on the same inputs;
 *   - each report names only its own project (the other project's names
 *     and numbers, and the demo's, are absent);
 *   - killed mid-run and resumed, the same review.json (timing aside);
 *   - the report loads in headless Chromium, every figure, no empty
 *     section (scripts/check-report.sh --complete);
 *   - a bad project file is refused in one line, exit 2.
 */
#include <cJSON.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/stat.h>
#include <time.h>
#include <cmocka.h>

#include "../scratch.h"
#include "../test_util.h"
#include "run_cli.h"

static struct cli_run r;
static char dir[] = "/tmp/stray_reviewXXXXXX";

#define STRAY(...) run_stray(&r, (char *[]){ "stray", __VA_ARGS__, NULL })
#define RAYS "20000"

static char *at(const char *leaf)
{
	static char p[16][512];
	static int k;
	char *s = p[k++ % 16];

	snprintf(s, 512, "%s/%s", dir, leaf);
	return s;
}

static char *slurp_all(const char *path)
{
	FILE *f = fopen(path, "rb");
	char *buf;
	long n;

	if (!f)
		return NULL;
	fseek(f, 0, SEEK_END);
	n = ftell(f);
	fseek(f, 0, SEEK_SET);
	buf = malloc((size_t)n + 1);
	if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n)
		n = 0;
	if (buf)
		buf[n] = '\0';
	fclose(f);
	return buf;
}

static cJSON *json_file(const char *path)
{
	char *t = slurp_all(path);
	cJSON *j = t ? cJSON_Parse(t) : NULL;

	free(t);
	if (!j)
		fail_msg("%s: missing or not JSON", path);
	return j;
}

static void ok(void)
{
	if (r.status != 0)
		fail_msg("status %d: %.600s", r.status, r.err);
}

static const cJSON *verdict(const cJSON *review, const char *req)
{
	const cJSON *v;

	cJSON_ArrayForEach(v, cJSON_GetObjectItem(review, "verdicts"))
		if (strcmp(cJSON_GetObjectItem(v, "requirement")->valuestring, req) == 0)
			return v;
	fail_msg("no verdict for %s", req);
	return NULL;
}

/* found == the number by hand (null both when not excluded) */
static void same(const cJSON *v, const cJSON *hand)
{
	const cJSON *f = cJSON_GetObjectItem(v, "found");

	assert_non_null(hand);
	if (cJSON_IsNull(hand)) {
		assert_true(cJSON_IsNull(f));
		assert_false(cJSON_IsTrue(cJSON_GetObjectItem(v, "pass")));
		return;
	}
	assert_true(cJSON_IsNumber(f));
	assert_near(f->valuedouble, hand->valuedouble, 1e-9);
}

static void no_text(const char *report, const char *const *words)
{
	char *t = slurp_all(report);
	int i;

	assert_non_null(t);
	for (i = 0; words[i]; i++)
		if (strstr(t, words[i]))
			fail_msg("%s names '%s' (another project's)", report, words[i]);
	free(t);
}

static void checked_in_chromium(const char *out)
{
	char cmd[1024];

	if (system("command -v chromium >/dev/null 2>&1") != 0)
		skip();
	snprintf(cmd, sizeof(cmd), "scripts/check-report.sh '%s' --complete >/dev/null", out);
	assert_int_equal(system(cmd), 0);
}

static void test_cube(void **state)
{
	static const char *const other[] = { "navcam", "51.6", "700 km",
		"inertial", "three-vane", "NAV", "st16-like", "550 km", "ref4",
		"three heads", NULL };
	char out[512];
	cJSON *rv, *hand;
	const cJSON *s;
	char heads[600];

	(void)state;
	snprintf(out, sizeof(out), "%s", at("cube"));	/* at() recycles */
	STRAY("review", "examples/review-cube/project.json", "--out", out,
	      "--rays", RAYS);
	ok();
	rv = json_file(at("cube/review.json"));
	assert_string_equal(cJSON_GetObjectItem(rv, "name")->valuestring,
			    "cube-st-1 baffle rev B");
	/* exclusion by hand, on the review's own system curve */
	STRAY("exclusion", "--curve", at("cube/system.csv"), "--sensor",
	      "examples/review-cube/sensor.json", "--rate", "3",
	      "--earth-albedo", "0.3", "--altitude-km", "500", "--json");
	ok();
	hand = cJSON_Parse(r.out);
	same(verdict(rv, "sun_exclusion_deg_max"), cJSON_GetObjectItem(hand, "sun_deg"));
	same(verdict(rv, "moon_exclusion_deg_max"), cJSON_GetObjectItem(hand, "moon_deg"));
	same(verdict(rv, "earth_exclusion_deg_max"), cJSON_GetObjectItem(hand, "earth_limb_deg"));
	assert_int_equal(cJSON_IsTrue(cJSON_GetObjectItem(verdict(rv, "moon_exclusion_deg_max"), "pass")),
			 cJSON_GetObjectItem(hand, "moon_deg")->valuedouble <= 12);
	cJSON_Delete(hand);
	/* availability by hand: the mission written from the same orbit */
	snprintf(heads, sizeof(heads), "{\"heads\": [{\"name\": \"P\", \"boresight_body\": [0, 0.64, -0.77], "
		 "\"up_body\": [1, 0, 0], \"table\": \"%s\"}, {\"name\": \"S\", \"boresight_body\": "
		 "[0, -0.64, -0.77], \"up_body\": [1, 0, 0], \"table\": \"%s\"}]}",
		 at("cube/flight_table.bin"), at("cube/flight_table.bin"));
	{
		FILE *f = fopen(at("hand_heads.json"), "w");

		assert_non_null(f);
		fputs(heads, f);
		fclose(f);
	}
	STRAY("availability", "--write-oem", at("hand.oem"), "--write-aem",
	      at("hand.aem"), "--altitude-km", "500", "--ltan", "10:30",
	      "--epoch", "2027-03-20", "--hours", "12", "--heads",
	      at("hand_heads.json"), "--json");
	ok();
	hand = cJSON_Parse(r.out);
	same(verdict(rv, "availability_min"), cJSON_GetObjectItem(hand, "any_head_available_frac"));
	cJSON_Delete(hand);
	/* the step with no input is listed with why, never filled */
	cJSON_ArrayForEach(s, cJSON_GetObjectItem(rv, "steps"))
		if (strcmp(cJSON_GetObjectItem(s, "name")->valuestring, "diagnose") == 0) {
			assert_string_equal(cJSON_GetObjectItem(s, "status")->valuestring, "not run");
			assert_non_null(strstr(cJSON_GetObjectItem(s, "why")->valuestring, "measured"));
		}
	cJSON_Delete(rv);
	no_text(at("cube/report.md"), other);
	no_text(at("cube/report.html"), other);
	checked_in_chromium(out);
}

static void test_navcam(void **state)
{
	static const char *const other[] = { "cube-st-1", "PORT", "STBD",
		"10:30", "500 km", "st16-like", "550 km", "ref4", "three heads",
		NULL };
	char out[512];
	cJSON *rv, *hand, *d;
	const cJSON *c;
	int named = 0;

	(void)state;
	snprintf(out, sizeof(out), "%s", at("nav"));
	STRAY("review", "examples/review-navcam/project.json", "--out", out,
	      "--rays", RAYS);
	ok();
	rv = json_file(at("nav/review.json"));
	STRAY("exclusion", "--curve", at("nav/system.csv"), "--sensor",
	      "examples/review-navcam/sensor.json", "--earth-albedo", "0.3",
	      "--altitude-km", "700", "--json");
	ok();
	hand = cJSON_Parse(r.out);
	same(verdict(rv, "sun_exclusion_deg_max"), cJSON_GetObjectItem(hand, "sun_deg"));
	same(verdict(rv, "moon_exclusion_deg_max"), cJSON_GetObjectItem(hand, "moon_deg"));
	cJSON_Delete(hand);
	{
		FILE *f = fopen(at("nav_heads.json"), "w");

		assert_non_null(f);
		fprintf(f, "{\"heads\": [{\"name\": \"N\", \"boresight_body\": [0.34, 0, -0.94], "
			"\"up_body\": [0, 1, 0], \"table\": \"%s\"}]}", at("nav/flight_table.bin"));
		fclose(f);
	}
	STRAY("availability", "--write-oem", at("n.oem"), "--write-aem",
	      at("n.aem"), "--altitude-km", "700", "--inclination-deg", "51.6",
	      "--attitude", "inertial", "--epoch", "2027-09-01", "--hours", "6",
	      "--gen-step-s", "30", "--heads", at("nav_heads.json"), "--json");
	ok();
	hand = cJSON_Parse(r.out);
	same(verdict(rv, "availability_min"), cJSON_GetObjectItem(hand, "any_head_available_frac"));
	cJSON_Delete(hand);
	/* the diagnosis names the coating hidden in the lab curve (0.09) */
	d = json_file(at("nav/diagnose.json"));
	cJSON_ArrayForEach(c, cJSON_GetObjectItem(d, "causes"))
		named += strcmp(cJSON_GetObjectItem(c, "name")->valuestring, "reflectance") == 0;
	assert_int_equal(named, 1);
	cJSON_Delete(d);
	cJSON_Delete(rv);
	no_text(at("nav/report.md"), other);
	no_text(at("nav/report.html"), other);
	checked_in_chromium(out);
}

/* review.json without its timing fields */
static cJSON *untimed(const char *path)
{
	cJSON *j = json_file(path), *s;

	cJSON_ArrayForEach(s, cJSON_GetObjectItem(j, "steps"))
		cJSON_DeleteItemFromObject(s, "seconds");
	return j;
}

static void test_killed_and_resumed(void **state)
{
	const char *bin = getenv("STRAY_BIN") ? getenv("STRAY_BIN") : "build/bin/stray";
	char out[512];
	struct timespec nap = { 0, 20000000 };
	cJSON *a, *b;
	pid_t pid;
	int st, k;

	(void)state;
	snprintf(out, sizeof(out), "%s", at("killed"));	/* at() recycles */
	/* the cube's review (test_cube ran it whole) killed after its first
	 * step, then resumed */
	pid = fork();
	if (pid == 0) {
		int null = open("/dev/null", O_WRONLY);

		dup2(null, 1);
		dup2(null, 2);
		execl(bin, "stray", "review", "examples/review-cube/project.json",
		      "--out", out, "--rays", RAYS, (char *)NULL);
		_exit(127);
	}
	for (k = 0; k < 1500 && access(at("killed/manifest.json"), F_OK) != 0; k++)
		nanosleep(&nap, NULL);
	kill(pid, SIGKILL);
	waitpid(pid, &st, 0);
	assert_true(WIFSIGNALED(st));	/* killed mid-run, not finished */
	assert_int_not_equal(access(at("killed/review.json"), F_OK), 0);
	STRAY("review", "examples/review-cube/project.json", "--out", out,
	      "--rays", RAYS, "--resume");
	ok();
	assert_non_null(strstr(r.err, "kept from the last run"));
	a = untimed(at("killed/review.json"));
	b = untimed(at("cube/review.json"));
	if (!cJSON_Compare(a, b, 1))
		fail_msg("resumed review.json differs from the whole run's");
	cJSON_Delete(a);
	cJSON_Delete(b);
	/* resumed again with nothing changed: every step kept */
	STRAY("review", "examples/review-cube/project.json", "--out", out,
	      "--rays", RAYS, "--resume");
	ok();
	assert_null(strstr(r.err, "s so far"));
}

static void put(const char *leaf, const char *text)
{
	FILE *f = fopen(at(leaf), "w");

	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

static void refused(const char *leaf, const char *word)
{
	STRAY("review", at(leaf), "--out", at("bad_out"));
	assert_int_equal(r.status, 2);
	assert_int_equal(r.err_lines, 1);
	assert_non_null(strstr(r.err, leaf));
	assert_non_null(strstr(r.err, word));
	assert_int_not_equal(access(at("bad_out"), F_OK), 0);
}

static void test_bad_projects(void **state)
{
	(void)state;
	put("p1.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\", "
	    "\"requirements\": {\"sun_exclusion_deg_max\": 30}, \"lenz\": \"ideal\"}");
	refused("p1.json", "lenz");
	put("p2.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\"}");
	refused("p2.json", "requirements");
	put("p3.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\", "
	    "\"requirements\": {\"sun_exclusion_max\": 30}}");
	refused("p3.json", "sun_exclusion_max");
	put("p4.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\", "
	    "\"requirements\": {\"availability_min\": 0.9}, \"heads\": "
	    "[{\"name\": \"A\", \"boresight_body\": [0,0,1], \"up_body\": [1,0,0]}]}");
	refused("p4.json", "heads");
	put("p5.json", "{\"sensor\": \"my.json\", \"scene\": \"ref4\", "
	    "\"requirements\": {\"availability_min\": 0.9}}");
	refused("p5.json", "my.json");
	put("p6.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\", "
	    "\"requirements\": {\"availability_min\": 0.9}, \"mission\": "
	    "{\"orbit\": {\"altitude_km\": 500, \"ltan\": \"25:00\"}}}");
	refused("p6.json", "25:00");
	/* JSON allows a key twice; a reader would keep one and drop the
	 * other requirement (found by fuzz_review_project: a sixth
	 * requirement overran the table) */
	put("p7.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\", "
	    "\"requirements\": {\"sun_exclusion_deg_max\": 30, \"moon_exclusion_deg_max\": 9, "
	    "\"earth_exclusion_deg_max\": 9, \"availability_min\": 0.9, "
	    "\"false_stars_per_image\": 5, \"sun_exclusion_deg_max\": 20}}");
	refused("p7.json", "given twice");
	/* a step that fails: listed as failed with its own message, the
	 * steps after it not run with why, the review still written, exit 1 */
	put("garbage.csv", "hello\n");
	put("p8.json", "{\"sensor\": \"st16-like\", \"scene\": \"ref4\", \"lens\": \"garbage.csv\", "
	    "\"requirements\": {\"sun_exclusion_deg_max\": 30}}");
	STRAY("review", at("p8.json"), "--out", at("p8_out"), "--rays", "1000");
	assert_int_equal(r.status, 1);
	{
		cJSON *rv = json_file(at("p8_out/review.json"));
		const cJSON *st;

		cJSON_ArrayForEach(st, cJSON_GetObjectItem(rv, "steps")) {
			const char *n = cJSON_GetObjectItem(st, "name")->valuestring;
			const char *status = cJSON_GetObjectItem(st, "status")->valuestring;
			const cJSON *why = cJSON_GetObjectItem(st, "why");

			if (strcmp(n, "trace") == 0) {
				assert_string_equal(status, "failed");
				assert_non_null(strstr(why->valuestring, "garbage.csv"));
			}
			if (strcmp(n, "exclusion") == 0) {
				assert_string_equal(status, "not run");
				assert_non_null(strstr(why->valuestring, "system.csv"));
			}
		}
		assert_true(cJSON_IsNull(cJSON_GetObjectItem(verdict(rv, "sun_exclusion_deg_max"), "found")));
		cJSON_Delete(rv);
	}
	/* --out an existing file: refused before any step */
	put("a_file", "x");
	STRAY("review", "examples/review-cube/project.json", "--out", at("a_file"));
	assert_int_equal(r.status, 2);
	assert_non_null(strstr(r.err, "not a folder"));
}

static int setup(void **state)
{
	(void)state;
	return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	return scratch_remove(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_bad_projects),
		cmocka_unit_test(test_cube),
		cmocka_unit_test(test_navcam),
		cmocka_unit_test(test_killed_and_resumed),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
