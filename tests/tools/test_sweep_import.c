/*
 * test_sweep_import.c - `stray sweep import` (issue 26, item 3) on frames
 * written by other software: tests/vectors/import/foreign (astropy and
 * tifffile, INDI's keywords, from the pixels of the simulated sweep in
 * tests/vectors/import/native; README.md there).  Imported and reduced,
 * they give the native folder's curve to the last bit; every mismatch
 * between the log and the headers is reported with its file and line,
 * and impossible input is refused with nothing written.
 *
 * STRAY_BIN=/path/to/old/stray runs the same against another build.
 */
#include <cJSON.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>
#include <cmocka.h>

#include "cli_fixture.h"

#define VEC "tests/vectors/import/"
#define FOREIGN VEC "foreign/"
#define LIGHT1 "CCD_Simulator_Light_001.fits"
#define LIGHT2 "CCD_Simulator_Light_002.fits"
#define HEAD "file,angle_deg,frametyp,exptime_s,ndtrans"

/* Bad input: exit 2, nothing on stdout, n stderr lines, each needle in
 * them, and no output folder (nor its temporary) left. */
static void expect_refused(int n, const char *const *needles)
{
	int k;

	if (r.status != 2 || r.err_lines != n)
		fail_msg("status %d, stderr (%d lines, wanted %d): %s",
			 r.status, r.err_lines, n, r.err);
	for (k = 0; needles[k]; k++)
		if (!strstr(r.err, needles[k]))
			fail_msg("stderr lacks '%s': %s", needles[k], r.err);
	assert_string_equal(r.out, "");
	assert_false(exists(in_dir("out")));
}

#define REFUSED(n, ...) expect_refused(n, (const char *[]){ __VA_ARGS__, NULL })

/* The curve of `stray --json reduce DIR`: n points' alpha and sigma. */
static size_t curve(const char *sweep, double *alpha, double *sigma)
{
	cJSON *j, *c, *p;
	size_t n = 0;

	STRAY("--json", "reduce", (char *)sweep, "--out", in_dir("c.csv"));
	if (r.status != 0)
		fail_msg("reduce %s: status %d: %s", sweep, r.status, r.err);
	j = cJSON_Parse(r.out);
	assert_non_null(j);
	c = cJSON_GetObjectItem(j, "curve");
	cJSON_ArrayForEach(p, c) {
		alpha[n] = cJSON_GetObjectItem(p, "alpha")->valuedouble;
		sigma[n] = cJSON_GetObjectItem(p, "sigma")->valuedouble;
		n++;
	}
	cJSON_Delete(j);
	return n;
}

/* Imported FITS (fmt "fits") or TIFF ("tiff") reduce to the native
 * sweep's curve, alpha and sigma equal to the last bit: same pixels,
 * same exposure, ND, angle, read-back angle (the log's, full precision)
 * and time, same Bayer phase (--col0/--row0). */
static void same_curve(const char *fmt)
{
	char log[160], frames[160];
	double a0[16], s0[16], a1[16], s1[16];
	size_t n0, n1, i;

	snprintf(log, sizeof(log), FOREIGN "log_%s.csv", fmt);
	snprintf(frames, sizeof(frames), FOREIGN "%s", fmt);
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      "--col0", "800", "--row0", "960", "--satlevel", "4095", frames);
	if (r.status != 0)
		fail_msg("import: status %d: %s", r.status, r.err);
	assert_non_null(strstr(r.out, "imported 24 frames"));
	n0 = curve(VEC "native", a0, s0);
	n1 = curve(in_dir("out"), a1, s1);
	assert_int_equal(n0, 3);
	assert_int_equal(n1, n0);
	for (i = 0; i < n0; i++) {
		print_message("%s: alpha %.17g native %.17g\n", fmt, a1[i], a0[i]);
		assert_true(a1[i] == a0[i] && s1[i] == s0[i]);
	}
}

static void test_fits_same_curve(void **state)
{
	(void)state;
	same_curve("fits");
}

static void test_tiff_same_curve(void **state)
{
	(void)state;
	same_curve("tiff");
}

/* The originals are copied byte for byte, and import.csv names them. */
static void test_originals_copied(void **state)
{
	char cmd[512];

	(void)state;
	STRAY("sweep", "import", "--log", FOREIGN "log_fits.csv", "--out",
	      in_dir("out"), FOREIGN "fits");
	assert_int_equal(r.status, 0);
	snprintf(cmd, sizeof(cmd), "cmp -s " FOREIGN "fits/" LIGHT2 " %s/"
		 "original/" LIGHT2 " && grep -q '," LIGHT2 ",' %s/import.csv",
		 in_dir("out"), in_dir("out"));
	assert_int_equal(system(cmd), 0);
}

/* A log naming a file not given: its line and the name. */
static void test_log_names_missing_file(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.024357,0.3\n"
		       "gone.fits,0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1);
	REFUSED(1, "log.csv:3: file 'gone.fits': is in the log but not "
		"among the files given");
}

/* A file given that the log does not list. */
static void test_file_not_in_log(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1, FOREIGN "fits/" LIGHT2);
	REFUSED(1, "fits/" LIGHT2 ": file '" LIGHT2 "': is not in the log");
}

/* The header's exposure (EXPTIME) against the log's. */
static void test_exposure_mismatch(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.05,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1);
	REFUSED(1, "log.csv:2: exptime_s '0.05': differs from the header's "
		"exposure 0.024357 s in " LIGHT1);
}

/* Frame type and filter against IMAGETYP and FILTER; three mismatches,
 * three lines and the count. */
static void test_every_mismatch_reported(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD ",filter\n" LIGHT1
		       ",0,DARK,0.024357,0.3,ND T=0.3\n" LIGHT2
		       ",0,FULL,0.024357,0.3,Clear\ngone.fits,0,FULL,1,1,\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1, FOREIGN "fits/" LIGHT2);
	REFUSED(4, "log.csv:2: frametyp 'DARK': disagrees with the header's "
		"light frame ('Light Frame') in " LIGHT1,
		"log.csv:3: filter 'Clear': differs from the header's FILTER "
		"'ND T=0.3' in " LIGHT2, "log.csv:4: file 'gone.fits'",
		"mismatches 3: between the log and the frames");
}

static void test_tiff_not_16bit_grey(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD "\ngray8.tif,0,FULL,1,1\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "hostile/gray8.tif");
	REFUSED(1, "gray8.tif: BitsPerSample '8': must be 16");
	log = put_text("log.csv", HEAD "\nrgb16.tif,0,FULL,1,1\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "hostile/rgb16.tif");
	REFUSED(1, "rgb16.tif: SamplesPerPixel '3': must be 1");
}

static void test_fits_no_exptime(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD "\nnoexptime.fits,0,FULL,1,1\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "hostile/noexptime.fits");
	REFUSED(1, "noexptime.fits: EXPTIME: missing (nor EXPOSURE)");
	log = put_text("log.csv", HEAD "\nfloat32.fits,0,FULL,1,1\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "hostile/float32.fits");
	REFUSED(1, "float32.fits: BITPIX: must be 16 with BZERO 32768");
}

static void test_nan_angle(void **state)
{
	char *log;

	(void)state;
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",nan,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1);
	REFUSED(1, "log.csv:2: angle_deg 'nan': is not a finite number");
}

/* One file given twice, or the same bytes under two names. */
static void test_duplicate_files(void **state)
{
	char *log, cmd[400];

	(void)state;
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1, FOREIGN "fits/" LIGHT1);
	REFUSED(1, LIGHT1 "': is a second file of that name");
	snprintf(cmd, sizeof(cmd), "cp " FOREIGN "fits/" LIGHT1 " %s",
		 in_dir("copy.fits"));
	assert_int_equal(system(cmd), 0);
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.024357,0.3\n"
		       "copy.fits,0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1, in_dir("copy.fits"));
	REFUSED(1, "copy.fits: file 'copy.fits': has the same bytes as");
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.024357,0.3\n"
		       LIGHT1 ",5,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      FOREIGN "fits/" LIGHT1);
	REFUSED(1, "log.csv:3: file '" LIGHT1 "': is logged twice");
}

/* Frames cut short: refused before anything is written, and no
 * temporary folder left beside the output. */
static void test_truncated_frames(void **state)
{
	char *log, cmd[600];

	(void)state;
	snprintf(cmd, sizeof(cmd), "head -c 3000 " FOREIGN "fits/" LIGHT1
		 " > %s && head -c 300 " FOREIGN "tiff/CCD_Simulator_Light_001"
		 ".tif > %s", in_dir("cut.fits"), in_dir("cut.tif"));
	assert_int_equal(system(cmd), 0);
	log = put_text("log.csv", HEAD "\ncut.fits,0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      in_dir("cut.fits"));
	REFUSED(1, "cut.fits: NAXIS1 x NAXIS2: claims more data than the "
		"file holds");
	log = put_text("log.csv", HEAD "\ncut.tif,0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("out"),
	      in_dir("cut.tif"));
	REFUSED(1, "cut.tif: StripOffsets", "pixels cannot be read");
	snprintf(cmd, sizeof(cmd), "ls -d %s.tmp.* 2>/dev/null | grep -q .",
		 in_dir("out"));
	assert_int_not_equal(system(cmd), 0);
}

/* A FITS card: key = value, padded to 80 characters. */
static void card(char *h, int *k, const char *text)
{
	snprintf(h + 80 * (*k)++, 81, "%-80s", text);
}

/* dir/fNNN.fits: 64 x 4 counts of value v, as a camera writes a light
 * frame (BITPIX 16, BZERO 32768, EXPTIME, IMAGETYP). */
static void camera_fits(int v)
{
	char h[2880 + 1], name[32], *path;
	unsigned char px[2880];
	int k = 0, i;
	FILE *f;

	memset(h, ' ', sizeof(h));
	card(h, &k, "SIMPLE  =                    T");
	card(h, &k, "BITPIX  =                   16");
	card(h, &k, "NAXIS   =                    2");
	card(h, &k, "NAXIS1  =                   64");
	card(h, &k, "NAXIS2  =                    4");
	card(h, &k, "BZERO   =                32768");
	card(h, &k, "BSCALE  =                    1");
	card(h, &k, "EXPTIME =                  1.0");
	card(h, &k, "IMAGETYP= 'Light Frame'");
	card(h, &k, "END");
	h[80 * k] = ' ';
	memset(px, 0, sizeof(px));
	for (i = 0; i < 64 * 4; i++) {	/* big-endian, top bit flipped */
		px[2 * i] = (unsigned char)(((v + 32768) >> 8) & 0xff);
		px[2 * i + 1] = (unsigned char)((v + 32768) & 0xff);
	}
	snprintf(name, sizeof(name), "frames/f%03d.fits", v);
	path = in_dir(name);
	f = fopen(path, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(h, 1, 2880, f), 2880);
	assert_int_equal(fwrite(px, 1, 2880, f), 2880);
	fclose(f);
}

/* Killed while it writes (its temporary folder and original/ there):
 * nothing is left, neither the folder nor its temporary. */
static void test_interrupted_leaves_nothing(void **state)
{
	const char *bin = getenv("STRAY_BIN") ? getenv("STRAY_BIN")
					      : "build/bin/stray";
	char *text = malloc(200 * 40 + 64), orig[300], tmp[256];
	size_t len;
	struct timespec ms = { 0, 10000000 };
	int i, st, seen = 0;
	pid_t pid;

	(void)state;
	assert_non_null(text);
	mkdir(in_dir("frames"), 0700);
	len = (size_t)sprintf(text, HEAD "\n");
	for (i = 0; i < 200; i++) {
		camera_fits(i);
		len += (size_t)sprintf(text + len, "f%03d.fits,%d,FULL,1,1\n", i,
				       i / 20);
	}
	put_text("log.csv", text);
	free(text);
	pid = fork();
	if (pid == 0) {
		freopen("/dev/null", "w", stdout);
		freopen("/dev/null", "w", stderr);
		execl(bin, "stray", "sweep", "import", "--log",
		      in_dir("log.csv"), "--out", in_dir("out"),
		      in_dir("frames"), (char *)NULL);
		_exit(127);
	}
	snprintf(tmp, sizeof(tmp), "%s.tmp.%ld", in_dir("out"), (long)pid);
	snprintf(orig, sizeof(orig), "%s/original", tmp);
	for (i = 0; i < 1000 && !seen; i++) {	/* at most 10 s */
		seen = exists(orig);
		if (!seen && waitpid(pid, &st, WNOHANG) == pid)
			break;
		nanosleep(&ms, NULL);
	}
	if (!seen)
		fail_msg("the import never began to write %s", orig);
	kill(pid, SIGTERM);
	waitpid(pid, &st, 0);
	assert_false(exists(tmp));
	assert_false(exists(in_dir("out")));
}

/* An output folder that exists with something in it is never touched. */
static void test_output_not_empty(void **state)
{
	char *log, *keep;

	(void)state;
	mkdir(in_dir("full"), 0700);
	keep = put_text("full/keep.txt", "mine\n");
	log = put_text("log.csv", HEAD "\n" LIGHT1 ",0,FULL,0.024357,0.3\n");
	STRAY("sweep", "import", "--log", log, "--out", in_dir("full"),
	      FOREIGN "fits/" LIGHT1);
	REFUSED(1, "full: exists and is not empty");
	assert_true(exists(keep));
	assert_false(exists(in_dir("full/manifest.csv")));
}

static int setup(void **state)
{
	(void)state;
	if (cli_setup("import"))
		return -1;
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	return cli_teardown();
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_fits_same_curve, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_tiff_same_curve, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_originals_copied, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_log_names_missing_file,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_file_not_in_log, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_exposure_mismatch, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_every_mismatch_reported,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_tiff_not_16bit_grey,
						setup, teardown),
		cmocka_unit_test_setup_teardown(test_fits_no_exptime, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_nan_angle, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_duplicate_files, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_truncated_frames, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_output_not_empty, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_interrupted_leaves_nothing,
						setup, teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
