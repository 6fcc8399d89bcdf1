/*
 * test_hardening.c - issue 14's probes of `stray` as a careless user or an
 * attacker would run them: each is bad input answered by one line and
 * exit status 2 (never a crash, a hang, exit 1 or exit 0), and a failed
 * or interrupted run leaves no output and no temporary behind.
 *
 * STRAY_BIN=/path/to/old/stray runs the same probes against another build
 * (how they were shown to fail before the fixes).
 */
#include <cJSON.h>
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/stat.h>
#include <time.h>
#include <cmocka.h>

#include "../test_util.h"
#include "cli_fixture.h"

/* No NAME.tmp.PID left in the folder. */
static int temporaries(void)
{
	DIR *d = opendir(dir);
	struct dirent *e;
	int n = 0;

	while (d && (e = readdir(d)))
		n += strstr(e->d_name, ".tmp.") != NULL;
	if (d)
		closedir(d);
	return n;
}

static int setup(void **state)
{
	(void)state;
	return cli_setup("hard");
}

static int teardown(void **state)
{
	(void)state;
	return cli_teardown();
}

static const char good[] = "theta_deg,alpha\n0,1\n10,0.1\n30,1e-4\n60,1e-8\n";

/* b'\r\r\n' * 66 was a double free (SIGABRT) in every curve reader. */
static void test_cr_lines_no_crash(void **state)
{
	char text[3 * 66];
	char *p;
	int k;

	(void)state;
	for (k = 0; k < 66; k++)
		memcpy(text + 3 * k, "\r\r\n", 3);
	p = put_bytes("cr.csv", text, sizeof(text));
	STRAY("exclusion", "--curve", p);
	expect_bad("no header row");
	STRAY("fdr", "--map", p);
	expect_bad("no header row");
}

static void test_unbounded_inputs(void **state)
{
	(void)state;
	STRAY("exclusion", "--curve", "/dev/zero");
	expect_bad("/dev/zero: is not a regular file");
	STRAY("exclusion", "--curve", dir);
	expect_bad("is a directory, not a file");
}

/* A curve of n rows, theta from 1 deg, sigma 5 %. */
static char *long_curve(const char *name, size_t n)
{
	char *text = malloc(64 + n * 40), *p;
	size_t i, len;

	assert_non_null(text);
	len = (size_t)sprintf(text, "theta_deg,alpha,sigma\n");
	for (i = 0; i < n; i++) {
		double t = 1.0 + 80.0 * (double)i / (double)n;

		len += (size_t)sprintf(text + len, "%.8f,%.6g,%.6g\n", t,
				       pow(10.0, -t / 10.0),
				       0.05 * pow(10.0, -t / 10.0));
	}
	p = put_bytes(name, text, len);
	free(text);
	return p;
}

/* 10^6 rows, or 2001 angles into diagnose: refused at once (diagnose ran
 * 12 s into "out of memory" on 10^5). */
static void test_row_and_angle_limits(void **state)
{
	(void)state;
	STRAY("diagnose", long_curve("rows.csv", 1000000), "--scene", "ref4");
	expect_bad("rows.csv:100002: row: more than 100000 rows");
	STRAY("diagnose", long_curve("angles.csv", 2001), "--scene", "ref4",
	      "--rays", "2000");
	expect_bad("theta_deg 2001: at most 2000 measured angles");
}

static void test_curve_physics(void **state)
{
	(void)state;
	STRAY("exclusion", "--curve",
	      put_text("zero.csv", "theta_deg,alpha\n5,0\n10,0\n"));
	expect_bad("every value is 0");
	STRAY("firmware-table", "--curve", in_dir("zero.csv"), "--out-bin",
	      in_dir("zero.bin"));
	expect_bad("every value is 0");
	assert_false(exists(in_dir("zero.bin")));
	STRAY("exclusion", "--curve", put_text("huge.csv",
	      "theta_deg,alpha\n0,1\n10,0.1\n1e300,1e-9\n"));
	expect_bad("huge.csv:4: theta_deg '1e+300': must be in [0, 180]");
	STRAY("firmware-table", "--curve", in_dir("huge.csv"), "--json");
	expect_bad("theta_deg '1e+300'");
	STRAY("exclusion", "--curve", put_text("neg.csv",
	      "theta_deg,alpha\n-400,1\n10,0.1\n"));
	expect_bad("theta_deg '-400'");
	/* a spreadsheet's byte-order mark is not part of the first name */
	STRAY("exclusion", "--curve", put_text("bom.csv",
	      "\xEF\xBB\xBFtheta_deg,alpha\n0,1\n10,0.1\n30,1e-4\n60,1e-8\n"));
	assert_int_equal(r.status, 0);
}

static void test_qe_above_one(void **state)
{
	(void)state;
	STRAY("exclusion", "--curve", put_text("c.csv", good), "--qe",
	      put_text("qe.csv", "wavelength_nm,qe\n400,0.5\n500,1.7\n"));
	expect_bad("qe.csv:3: qe '1.7': a quantum efficiency must be <= 1");
}

static void test_exclusion_never_nan(void **state)
{
	(void)state;
	STRAY("exclusion", "--curve",
	      put_text("moon.csv", "theta_deg,alpha\n0,1\n10,0.5\n"));
	assert_int_equal(r.status, 0);
	if (strstr(r.out, "nan"))
		fail_msg("'nan' in: %s", r.out);
}

static void test_trace_refusals(void **state)
{
	char *zero = put_text("lens0.csv", "theta_deg,alpha\n0,0\n90,0\n");

	(void)state;
	STRAY("trace", "--scene", "nosuch", "--out", in_dir("o.csv"));
	expect_bad("nosuch: --scene: is neither a built-in scene");
	STRAY("trace", "--scene", "ref4", "--angles", "0,10", "--rays", "2000",
	      "--lens", zero, "--out", in_dir("o.csv"));
	expect_bad("lens0.csv:2: alpha '0'");
	/* a plate between the beam and the detector: P(0) = 0 */
	put_text("plate.obj", "v -50 -50 -20\nv 50 -50 -20\nv 50 50 -20\n"
		 "v -50 50 -20\nf 1 2 3\nf 1 3 4\n");
	STRAY("trace", "--scene", put_text("plate.json",
	      "{ \"meshes\": [ { \"file\": \"plate.obj\" } ],"
	      " \"materials\": { \"dead\": { \"type\": \"absorber\" } },"
	      " \"default_material\": \"dead\","
	      " \"detector\": { \"shape\": \"disk\", \"center\": [0, 0, -40],"
	      " \"normal\": [0, 0, 1], \"radius_mm\": 6.5 },"
	      " \"beam\": { \"center\": [0, 0, 0], \"normal\": [0, 0, 1],"
	      " \"radius_mm\": 14 } }"), "--angles", "0,10", "--rays", "2000",
	      "--out", in_dir("o.csv"));
	expect_bad("no on-axis power reaches the detector");
	assert_false(exists(in_dir("o.csv")));
	/* a NaN vertex is named, not "No meshes remaining" */
	put_text("plate.obj", "v -50 -50 -20\nv 50 -50 nan\nv 50 50 -20\n"
		 "f 1 2 3\n");
	STRAY("trace", "--scene", in_dir("plate.json"), "--out",
	      in_dir("o.csv"));
	expect_bad("plate.obj:2: mesh: a vertex coordinate is not a finite");
}

/* A failed run writes nothing: --out is not left behind by a bad --plot. */
static void test_trace_all_or_nothing(void **state)
{
	(void)state;
	STRAY("trace", "--scene", "ref4", "--angles", "0,10", "--rays", "2000",
	      "--out", in_dir("t.csv"), "--dump-paths", in_dir("d.csv"),
	      "--export-obj", in_dir("m.obj"), "--plot", "/nonexistent/p.png");
	assert_int_not_equal(r.status, 0);
	assert_int_equal(r.err_lines, 1);
	assert_false(exists(in_dir("t.csv")));
	assert_false(exists(in_dir("d.csv")));
	assert_false(exists(in_dir("m.obj")));
	assert_int_equal(temporaries(), 0);
	/* and a good run writes them all */
	STRAY("trace", "--scene", "ref4", "--angles", "0,10", "--rays", "2000",
	      "--out", in_dir("t.csv"), "--dump-paths", in_dir("d.csv"),
	      "--export-obj", in_dir("m.obj"), "--plot", in_dir("p.png"));
	assert_int_equal(r.status, 0);
	assert_true(exists(in_dir("t.csv")) && exists(in_dir("d.csv")) &&
		    exists(in_dir("m.obj")) && exists(in_dir("p.png")));
	assert_int_equal(temporaries(), 0);
	/* orbit: its CSV is not left by a plot that cannot be written */
	STRAY("firmware-table", "--curve", put_text("c.csv", good),
	      "--out-bin", in_dir("t.bin"));
	STRAY("orbit", "--table", in_dir("t.bin"), "--hours", "1", "--out",
	      in_dir("orbit1.csv"), "--plot", "/nonexistent/orbit");
	assert_int_not_equal(r.status, 0);
	assert_false(exists(in_dir("orbit1.csv")));
	assert_int_equal(temporaries(), 0);
	/* sweep: its table is not left by a plot that cannot be written */
	STRAY("sweep", "--scene", "ref4", "--state", in_dir("sw"), "--grid",
	      "reflectance=0.02,0.04", "--rays", "1000", "--angles", "0,10,20",
	      "--alpha-at", "10", "--out", in_dir("sw.csv"), "--plot",
	      "/nonexistent/sw.png");
	assert_int_not_equal(r.status, 0);
	assert_false(exists(in_dir("sw.csv")));
	assert_int_equal(temporaries(), 0);
}

static void test_option_checks(void **state)
{
	(void)state;
	STRAY("firmware-table", "--curve", put_text("c.csv", good), "--name",
	      "1bad name;", "--out-c", in_dir("t.c"));
	expect_bad("'--name': '1bad name;' is not a C identifier");
	assert_false(exists(in_dir("t.c")));
	STRAY("orbit", "--table", in_dir("t.bin"), "--epoch", "2026-02-30");
	expect_bad("'--epoch': '2026-02-30'");
	STRAY("sweep", "--scene", "ref4", "--state", in_dir("st1"), "--grid",
	      "length_mm=40", "--alpha-at", "500");
	expect_bad("--alpha-at 500");
	STRAY("sweep", "--scene", "ref4", "--state", in_dir("st2"), "--grid",
	      "bogus=1,2", "--rays", "1000", "--angles", "0,10");
	expect_bad("--grid 'bogus'");
	STRAY("sweep", "--scene", "ref4", "--state", in_dir("st3"), "--grid",
	      "pupil_z=1,2", "--grid", "pupil_z=3");
	expect_bad("key given twice");
}

static void test_messages_escaped(void **state)
{
	(void)state;
	STRAY("exclusion", "--curve", put_text("c.csv", good), "--sensor",
	      "\033[2J\001garbage");
	expect_bad("\\x1b[2J\\x01garbage");
	assert_null(strchr(r.err, '\033'));
}

static void test_exit_codes(void **state)
{
	char *file = put_text("plain.csv", good);

	(void)state;
	STRAY("reduce", file, "--out", in_dir("r.csv"));
	expect_bad("is a file, not a sweep folder");
	assert_false(exists(in_dir("r.csv")));
	STRAY("report", in_dir("nosuch"));
	expect_bad("nosuch: DIR: is not a folder");
	STRAY("fdr", "--map", put_text("dark.csv",
	      "fraction,rel_alpha\n0.5,0\n0.5,0\n"));
	expect_bad("every region is dark");
	assert_null(strstr(r.err, ": ok"));
}

static void test_report_escapes_and_malformed(void **state)
{
	char html[1 << 14];

	(void)state;
	mkdir(in_dir("rep"), 0700);
	put_text("rep/photometry.json", "{ \"sun\": ");
	STRAY("report", in_dir("rep"), "--title", "<script>alert(1)</script>");
	assert_int_equal(r.status, 0);
	slurp(in_dir("rep/report.html"), html, sizeof(html));
	assert_null(strstr(html, "<script>alert"));
	assert_non_null(strstr(html, "&lt;script&gt;alert(1)"));
	assert_non_null(strstr(html, "photometry.json is malformed"));
}

/* SIGINT while orbit writes its CSV (the temporary exists): no piece left
 * (was NAME.tmp.PID). */
static void test_interrupt_leaves_no_pieces(void **state)
{
	const char *bin = getenv("STRAY_BIN") ? getenv("STRAY_BIN")
					      : "build/bin/stray";
	pid_t pid;
	int st;

	(void)state;
	STRAY("firmware-table", "--curve", put_text("c.csv", good),
	      "--out-bin", in_dir("t.bin"));
	assert_int_equal(r.status, 0);
	pid = fork();
	if (pid == 0) {
		int null = open("/dev/null", O_WRONLY);

		dup2(null, 1);
		dup2(null, 2);
		execl(bin, "stray", "orbit", "--table", in_dir("t.bin"),
		      "--hours", "100", "--step-s", "1", "--out",
		      in_dir("orbit.csv"), (char *)NULL);
		_exit(127);
	}
	{	/* wait (1 ms polls, at most 60 s) until it writes */
		struct timespec ts = { 0, 1000000L };
		int i;

		for (i = 0; i < 60000 && temporaries() == 0 &&
			    waitpid(pid, &st, WNOHANG) == 0; i++)
			nanosleep(&ts, NULL);
		assert_int_equal(temporaries(), 1);
	}
	kill(pid, SIGINT);
	waitpid(pid, &st, 0);
	/* the invariant whenever the signal lands: no temporary, and the
	 * output either whole (it had finished) or absent */
	if (WIFSIGNALED(st))
		assert_false(exists(in_dir("orbit.csv")));
	else
		assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
	assert_int_equal(temporaries(), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cr_lines_no_crash),
		cmocka_unit_test(test_unbounded_inputs),
		cmocka_unit_test(test_row_and_angle_limits),
		cmocka_unit_test(test_curve_physics),
		cmocka_unit_test(test_qe_above_one),
		cmocka_unit_test(test_exclusion_never_nan),
		cmocka_unit_test(test_trace_refusals),
		cmocka_unit_test(test_trace_all_or_nothing),
		cmocka_unit_test(test_option_checks),
		cmocka_unit_test(test_messages_escaped),
		cmocka_unit_test(test_exit_codes),
		cmocka_unit_test(test_report_escapes_and_malformed),
		cmocka_unit_test(test_interrupt_leaves_no_pieces),
	};

	if (getenv("STRAY_TEST_FILTER"))	/* e.g. to skip /dev/zero */
		cmocka_set_test_filter(getenv("STRAY_TEST_FILTER"));
	return cmocka_run_group_tests(tests, setup, teardown);
}
