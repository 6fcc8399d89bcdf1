/*
 * test_cmd_trace.c - `stray trace` as a user runs it: help, the curve CSV
 * (formats.md, alpha(0) = 1, sigma and order columns), the same bytes for
 * any --threads, the --json summary, OBJ export, and one-line errors with
 * exit 2 for bad input.
 */
#include <cJSON.h>

#include "tracer_cli.h"
#include "stray/curve_io.h"

static void test_cmd_trace_help(void **state)
{
	char *argv[] = { "stray", "trace", "--help", NULL };
	struct cli_run r;

	(void)state;
	assert_int_equal(run_stray(&r, argv), 0);
	assert_non_null(strstr(r.out, "usage: stray trace"));
	assert_string_equal(r.err, "");
}

/* The two files differ only in their command line (diff -I). */
static int same_but_command(const char *a, const char *b)
{
	char *argv[] = { "diff", "-q", "-I", "^# command: ", (char *)a,
			 (char *)b, NULL };
	pid_t pid = fork();
	int st;

	if (pid == 0) {
		execvp("diff", argv);
		_exit(127);
	}
	waitpid(pid, &st, 0);
	return WIFEXITED(st) && WEXITSTATUS(st) == 0;
}

static void trace_to(const char *out, const char *threads)
{
	char *argv[] = { "stray", "trace", "--scene", "ref4", "--angles",
			 "0,20,40:50:5", "--rays", "20000", "--set",
			 "segments=128", "--threads", (char *)threads, "--out",
			 (char *)out, NULL };
	struct cli_run r;

	assert_int_equal(run_stray(&r, argv), 0);
	assert_string_equal(r.err, "");
}

static void test_cmd_trace_curve_csv(void **state)
{
	struct stray_curve c;
	char a[] = "/tmp/trace_aXXXXXX", b[] = "/tmp/trace_bXXXXXX";
	size_t k;

	(void)state;
	close(mkstemp(a));
	close(mkstemp(b));
	trace_to(a, "1");
	trace_to(b, "2");
	assert_int_equal(stray_curve_load(a, &c, NULL), 0);
	assert_int_equal(c.n, 5);
	assert_near(c.theta_deg[4], 50.0, 0.0);
	assert_near(c.alpha[0], 1.0, 1e-12);
	assert_non_null(c.sigma);
	assert_true(c.sigma[3] > 0.0 && c.sigma[3] < 0.2 * c.alpha[3]);
	assert_int_equal(c.n_extra, 4);
	for (k = 0; k < c.n; k++)	/* direct + orders add up to alpha */
		assert_near(c.extra[0][k] + c.extra[1][k] + c.extra[2][k] +
			    c.extra[3][k], c.alpha[k], 1e-9 * c.alpha[k]);
	assert_string_equal(c.extra_name[1], "order1");
	stray_curve_free(&c);
	/* bit-identical for any thread count (but the command line) */
	assert_true(same_but_command(a, b));
	unlink(a);
	unlink(b);
}

static void trace_light(const char *out, const char *flag)
{
	char *argv[] = { "stray", "trace", "--scene", "ref4", "--angles",
			 "0,88,89.5", "--rays", "20000", "--threads", "2",
			 "--out", (char *)out, (char *)flag, NULL };
	struct cli_run r;

	assert_int_equal(run_stray(&r, argv), 0);
	assert_string_equal(r.err, "");
}

/* 1 when the CSV's source line says B ran. */
static int says_light(const char *path)
{
	char line[512];
	int said = 0;
	FILE *f = fopen(path, "r");

	assert_non_null(f);
	while (fgets(line, sizeof(line), f))
		said |= strstr(line, "# source:") &&
			strstr(line, "light-side single scatter");
	fclose(f);
	return said;
}

/* --light-paths is the default (said in the CSV), byte for byte;
 * --no-light-paths is the detector-side estimator alone: no such line,
 * the same curve within 4 sigma, a larger sigma at 89.5 deg. */
static void test_cmd_trace_light_paths(void **state)
{
	char a[] = "/tmp/trace_aXXXXXX", b[] = "/tmp/trace_bXXXXXX",
	     c[] = "/tmp/trace_cXXXXXX";
	struct stray_curve ca, cb;

	(void)state;
	close(mkstemp(a));
	close(mkstemp(b));
	close(mkstemp(c));
	trace_light(a, NULL);
	trace_light(b, "--no-light-paths");
	trace_light(c, "--light-paths");
	assert_true(same_but_command(a, c));
	assert_false(same_but_command(a, b));
	assert_true(says_light(a));
	assert_false(says_light(b));
	assert_int_equal(stray_curve_load(b, &ca, NULL), 0);
	assert_int_equal(stray_curve_load(a, &cb, NULL), 0);
	assert_near(cb.alpha[2], ca.alpha[2],
		    4.0 * hypot(ca.sigma[2], cb.sigma[2]));
	assert_true(cb.sigma[2] < ca.sigma[2]);	/* B took part */
	stray_curve_free(&ca);
	stray_curve_free(&cb);
	unlink(a);
	unlink(b);
	unlink(c);
}

static void test_cmd_trace_json_and_export(void **state)
{
	char obj[] = "/tmp/trace_objXXXXXX";
	char *argv[] = { "stray", "trace", "--scene", "ref4", "--angles", "30",
			 "--rays", "4000", "--json", "--export-obj", obj, NULL };
	struct cli_run r;
	cJSON *j, *pps;
	FILE *f;
	char line[128];
	int groups = 0;

	(void)state;
	close(mkstemp(obj));
	assert_int_equal(run_stray(&r, argv), 0);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	pps = cJSON_GetObjectItem(j, "paths_per_s");
	assert_true(cJSON_IsNumber(pps) && pps->valuedouble > 0.0);
	assert_int_equal(cJSON_GetObjectItem(j, "angles")->valueint, 1);
	cJSON_Delete(j);
	f = fopen(obj, "r");
	assert_non_null(f);
	while (fgets(line, sizeof(line), f))
		groups += strncmp(line, "g vane3_bevel", 13) == 0;
	fclose(f);
	unlink(obj);
	assert_int_equal(groups, 1);
}

/* The path report, sample-path dump, map and plots are written. */
static void test_cmd_trace_extras(void **state)
{
	char paths[] = "/tmp/trace_pXXXXXX", png[] = "/tmp/trace_gXXXXXX";
	char dump[] = "/tmp/trace_dXXXXXX", map[] = "/tmp/trace_mXXXXXX";
	char *argv[] = { "stray", "trace", "--scene", "ref4", "--angles",
			 "0,60", "--rays", "8000", "--set", "segments=64",
			 "--paths-out", paths, "--plot", png, "--dump-paths",
			 dump, "--map", map, "--map-angle", "60", "--top", "2",
			 NULL };
	struct cli_run r;
	char line[256];
	FILE *f;

	(void)state;
	close(mkstemp(paths));
	close(mkstemp(png));
	close(mkstemp(dump));
	close(mkstemp(map));
	assert_int_equal(run_stray(&r, argv), 0);
	assert_non_null(strstr(r.out, "bevel"));	/* fig. 5.7: bevels lit */
	f = fopen(paths, "r");
	assert_non_null(f);
	while (fgets(line, sizeof(line), f) && line[0] == '#')
		;
	fclose(f);
	assert_string_equal(line, "theta_deg,path,n_scatter,alpha_part,sigma,"
			    "alpha_per_rho\n");
	f = fopen(png, "rb");
	assert_non_null(f);
	assert_int_equal(fread(line, 1, 4, f), 4);
	fclose(f);
	assert_memory_equal(line, "\x89PNG", 4);
	unlink(paths);
	unlink(png);
	unlink(dump);
	unlink(map);
}

static void test_cmd_trace_bad_input(void **state)
{
	char lens[] = "/tmp/trace_lensXXXXXX";
	int fd;
	char *a1[] = { "stray", "trace", "--scene", "ref4", "--rays", "abc",
		       "--out", "/tmp/x.csv", NULL };
	char *a2[] = { "stray", "trace", "--scene", "ref4", "--angles",
		       "0,95:10:1", "--out", "/tmp/x.csv", NULL };
	char *a3[] = { "stray", "trace", "--scene", "ref4", "--set",
		       "edge_radius=5", "--out", "/tmp/x.csv", NULL };
	char *a4[] = { "stray", "trace", "--scene", "ref4", "--lens", lens,
		       "--angles", "0", "--out", "/tmp/x.csv", NULL };
	char *a5[] = { "stray", "trace", "--out", "/tmp/x.csv", NULL };

	(void)state;
	expect_bad(a1, "--rays");
	expect_bad(a2, "95:10:1");
	expect_bad(a3, "edge_radius");
	fd = mkstemp(lens);
	assert_true(write(fd, "theta_deg,alpha\n0,1\n10,nan\n", 27) == 27);
	close(fd);
	expect_bad(a4, "lens");
	unlink(lens);
	expect_bad(a5, "--scene");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cmd_trace_help),
		cmocka_unit_test(test_cmd_trace_curve_csv),
		cmocka_unit_test(test_cmd_trace_json_and_export),
		cmocka_unit_test(test_cmd_trace_light_paths),
		cmocka_unit_test(test_cmd_trace_extras),
		cmocka_unit_test(test_cmd_trace_bad_input),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
