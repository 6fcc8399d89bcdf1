/*
 * test_hardening2_misc.c - issue 31's generic probes: an output that
 * would replace an input (or another output) of the run, a mesh too big
 * for the tracer, a sensor of 1e10 pixels, a full disk, the saturated
 * frames' tail, and a title that is HTML.  Each is refused as bad input
 * (one line, exit 2) before anything is written, or written correctly.
 *
 * STRAY_BIN=/path/to/old/stray runs the same probes against another build
 * (how they were shown to fail before the fixes).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "../test_util.h"
#include "cli_fixture.h"

/* CPU seconds the finished child commands used: "refused before the
 * work" is a bound on work done, which a loaded machine's wall clock
 * would not measure (a timer in a test is a flake). */
static double children_cpu_s(void)
{
	struct rusage ru;

	getrusage(RUSAGE_CHILDREN, &ru);
	return (double)ru.ru_utime.tv_sec + (double)ru.ru_stime.tv_sec +
	       1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static int setup(void **state)
{
	(void)state;
	return cli_setup("hard2");
}

static int teardown(void **state)
{
	(void)state;
	return cli_teardown();
}

static const char lab[] = "theta_deg,alpha,sigma\n5,1e-3,1e-4\n"
	"10,1e-4,1e-5\n20,1e-6,1e-7\n40,1e-8,1e-9\n";
static const char curve[] = "theta_deg,alpha\n0,1\n10,0.1\n30,1e-4\n60,1e-8\n";

/* `diagnose m.csv --write-model m.csv` replaced the lab data with a scene
 * file (exit 0): refused before the diagnosis, the data untouched. */
static void test_output_replaces_input(void **state)
{
	char *m = put_text("m.csv", lab), *c = put_text("c.csv", curve);
	double cpu0 = children_cpu_s();

	(void)state;
	STRAY("diagnose", m, "--scene", "ref4", "--write-model", m);
	expect_bad("m.csv: --write-model: is also an input of this run");
	assert_string_equal(slurp_file(m), lab);
	assert_true(children_cpu_s() - cpu0 < 5.0);
	/* a hard link is the same file */
	assert_int_equal(link(c, in_dir("hard.csv")), 0);
	STRAY("photometer", "--truth", c, "--out", in_dir("hard.csv"));
	expect_bad("is also an input of this run");
	assert_string_equal(slurp_file(c), curve);
	/* --opt=value spelling, and the option's value in another folder
	 * spelling (dir/./c.csv) */
	{
		char other[160];

		snprintf(other, sizeof(other), "--out=%s/./c.csv", dir);
		STRAY("photometer", "--truth", c, other);
		expect_bad("is also an input of this run");
	}
	assert_string_equal(slurp_file(c), curve);
}

/* Two outputs of one name: the second overwrote the first (exit 0). */
static void test_output_named_twice(void **state)
{
	char *c = put_text("c.csv", curve);
	char dotted[160];

	(void)state;
	STRAY("firmware-table", "--curve", c, "--out-c", in_dir("t.c"),
	      "--out-bin", in_dir("t.c"));
	expect_bad("t.c: --out-bin: is named twice as an output");
	assert_false(exists(in_dir("t.c")));
	snprintf(dotted, sizeof(dotted), "%s/./p.png", dir);
	STRAY("exclusion", "--curve", c, "--plot", in_dir("p.png"),
	      "--plot", dotted);
	expect_bad("is named twice as an output");
	assert_false(exists(in_dir("p.png")));
	/* diagnose --write-model S.json also writes S.obj */
	STRAY("diagnose", put_text("m.csv", lab), "--scene", "ref4",
	      "--write-model", in_dir("s.json"), "--plot", in_dir("s.obj"));
	expect_bad("is named twice as an output");
}

/* An abbreviated option escapes the early check: the library refuses
 * when the output is opened, nothing written. */
static void test_library_guard(void **state)
{
	char *m = put_text("m.csv", lab);

	(void)state;
	STRAY("diagnose", m, "--scene", "ref4", "--write-mod", m);
	assert_int_equal(r.status, 2);
	assert_non_null(strstr(r.err, "m.csv: is also an input of this run"));
	assert_string_equal(slurp_file(m), lab);
}

static int is_dev_full(void)
{
	struct stat st;

	return stat("/dev/full", &st) == 0 && S_ISCHR(st.st_mode);
}

/* A full disk: a plot said nothing and exited 0 (PLplot ignores it). */
static void test_full_disk_named(void **state)
{
	char *c = put_text("c.csv", curve);

	(void)state;
	if (!is_dev_full())
		skip();
	STRAY("exclusion", "--curve", c, "--plot", "/dev/full");
	assert_int_equal(r.status, 1);
	assert_non_null(strstr(r.err, "/dev/full: No space left on device"));
	STRAY("fdr", "--plot", "/dev/full");
	assert_int_equal(r.status, 1);
	assert_non_null(strstr(r.err, "/dev/full: No space left on device"));
	STRAY("frames", "--alpha", "1e-6", "--window", "64", "--png",
	      "/dev/full");
	assert_int_equal(r.status, 1);
	assert_non_null(strstr(r.err, "No space left on device"));
	assert_true(is_dev_full());	/* written in place, never replaced */
}

/* 6 M faces in 48 MB: 1.84 GB and 15 s of import before the refusal. */
static void test_mesh_counted_first(void **state)
{
	char *obj = in_dir("big.obj");
	FILE *f = fopen(obj, "wb");
	double cpu0;
	long i;

	(void)state;
	assert_non_null(f);
	fputs("v 0 0 -20\nv 1 0 -20\nv 0 1 -20\n", f);
	for (i = 0; i < 6000000; i++)
		fputs("f 1 2 3\n", f);
	fclose(f);
	put_text("big.json", "{ \"meshes\": [ { \"file\": \"big.obj\" } ],"
	    " \"materials\": { \"dead\": { \"type\": \"absorber\" } },"
	    " \"default_material\": \"dead\","
	    " \"detector\": { \"shape\": \"disk\", \"center\": [0, 0, -40],"
	    " \"normal\": [0, 0, 1], \"radius_mm\": 6.5 },"
	    " \"beam\": { \"center\": [0, 0, 0], \"normal\": [0, 0, 1],"
	    " \"radius_mm\": 14 } }");
	cpu0 = children_cpu_s();
	STRAY("trace", "--scene", in_dir("big.json"), "--angles", "0,10",
	      "--out", in_dir("o.csv"));
	expect_bad("big.obj: triangles 'at least");
	assert_true(children_cpu_s() - cpu0 < 5.0);
	assert_false(exists(in_dir("o.csv")));
}

/* Sensors of 1e10 pixels asked for 2^63 bytes; half pixels were taken. */
static void test_sensor_pixels(void **state)
{
	char *c = put_text("c.csv", curve);

	(void)state;
	STRAY("frames", "--alpha", "1e-6", "--sensor",
	      put_text("big.json", "{ \"pixels_x\": 1e5, \"pixels_y\": 1e5 }"));
	expect_bad("big.json: pixels_x 100000: must be <= 65536");
	STRAY("exclusion", "--curve", c, "--sensor",
	      put_text("half.json", "{ \"pixels_x\": 2592.5 }"));
	expect_bad("half.json: pixels_x 2592.5: must be a whole number");
	STRAY("exclusion", "--curve", c, "--sensor",
	      put_text("area.json", "{ \"pixels_x\": 60000, \"pixels_y\": 60000 }"));
	expect_bad("pixels_x * pixels_y must be <= 1e8");
}

/* alpha 0.1: "incomplete-gamma series did not converge", exit 1; then
 * white frames called in agreement with the model (issue 28): now refused
 * as light that fills every pixel to the ADC's full scale. */
static void test_frames_bright_alpha(void **state)
{
	(void)state;
	STRAY("frames", "--alpha", "0.1", "--window", "64");
	expect_bad("fills every pixel to the 12-bit ADC's full scale");
	assert_null(strstr(r.err, "converge"));
}

/* report.md kept a raw <script> title (report.html escaped it). */
static void test_report_md_escaped(void **state)
{
	char md[160];

	(void)state;
	STRAY("report", dir, "--title", "<script>alert(1)</script> a|b");
	assert_int_equal(r.status, 0);
	snprintf(md, sizeof(md), "%s/report.md", dir);
	assert_null(strstr(slurp_file(md), "<script>"));
	assert_non_null(strstr(slurp_file(md),
			       "# &lt;script&gt;alert(1)&lt;/script&gt; a\\|b"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_output_replaces_input,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_output_named_twice,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_library_guard, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_full_disk_named, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_mesh_counted_first, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_sensor_pixels, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_frames_bright_alpha, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_report_md_escaped, setup,
						teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
