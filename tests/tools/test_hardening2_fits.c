/*
 * test_hardening2_fits.c - issue 31's probes of the FITS readers and
 * writers and of sweep folders: a manifest's file names and the output
 * paths reach the disk as given (cfitsio's "(", "[" and "!" are not
 * instructions), a listed file is a plain file of the folder (no symlink,
 * no FIFO), sizes a header claims are held to the file's bytes before
 * any memory is taken, the manifest's SHA-256 and every frame's EXPTIME
 * are honoured by flightcheck, a duplicated row is named by its line.
 *
 * STRAY_BIN=/work/old/bin/stray runs the same probes against the build
 * before the fixes (each fails there).  A child that could hang (a FIFO)
 * or fill the memory runs under alarm() and RLIMIT_AS.
 */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <cmocka.h>
#include <cJSON.h>

/* a hang is killed, a 1 GB allocation fails (run_cli.h) */
#define STRAY(...) \
	run_stray_limited(&r, (char *[]){ "stray", __VA_ARGS__, NULL })
#include "cli_fixture.h"

#define MAKE_FLIGHT "build/tests/flightcheck/make_flight"
#define FRAME(k) "a+000.000_FULL_00" #k ".fits"

static void sh(const char *fmt, ...)
{
	char cmd[2048];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(cmd, sizeof(cmd), fmt, ap);
	va_end(ap);
	assert_int_equal(system(cmd), 0);
}

/* The SHA-256 of a file, as manifest.csv writes it. */
static void sha_of(const char *path, char hex[65])
{
	char cmd[700];
	FILE *p;

	snprintf(cmd, sizeof(cmd), "sha256sum '%s'", path);
	p = popen(cmd, "r");
	assert_non_null(p);
	assert_int_equal(fscanf(p, "%64s", hex), 1);
	pclose(p);
}

/*
 * Row `line` (1-based file line) of folder's manifest.csv rewritten:
 * its file name (when name), its exptime (when exptime) and its SHA-256
 * (of the named file's bytes now, when rehash).
 */
static void edit_row(const char *folder, int line, const char *name,
		     const char *exptime, int rehash)
{
	char path[300], lines[16][2200], cell[7][300], hex[65], file[600];
	FILE *f;
	int n = 0, i, c;

	snprintf(path, sizeof(path), "%s/manifest.csv", folder);
	f = fopen(path, "r");
	assert_non_null(f);
	while (n < 16 && fgets(lines[n], sizeof(lines[n]), f))
		n++;
	fclose(f);
	assert_true(line >= 2 && line <= n);
	for (c = 0, i = 0; c < 7; c++) {
		int k = 0;

		while (lines[line - 1][i] && lines[line - 1][i] != ',' &&
		       lines[line - 1][i] != '\n')
			cell[c][k++] = lines[line - 1][i++];
		cell[c][k] = '\0';
		i++;
	}
	if (exptime)
		snprintf(cell[3], sizeof(cell[3]), "%s", exptime);
	if (rehash) {
		snprintf(file, sizeof(file), "%s/%s", folder, cell[0]);
		sha_of(file, hex);
		snprintf(cell[6], sizeof(cell[6]), "%s", hex);
	}
	if (name)
		snprintf(cell[0], sizeof(cell[0]), "%s", name);
	snprintf(lines[line - 1], sizeof(lines[0]), "%s,%s,%s,%s,%s,%s,%s\n",
		 cell[0], cell[1], cell[2], cell[3], cell[4], cell[5],
		 cell[6]);
	f = fopen(path, "w");
	assert_non_null(f);
	for (i = 0; i < n; i++)
		fputs(lines[i], f);
	fclose(f);
}

/* The value of header card key (found in the first 2880 x 4 bytes)
 * replaced by value, right-justified in columns 11-30 as FITS writes
 * numbers. */
static void set_card(const char *path, const char *key, const char *value)
{
	char head[2880 * 4], want[9], card[81];
	FILE *f = fopen(path, "r+b");
	size_t n, at;

	assert_non_null(f);
	n = fread(head, 1, sizeof(head), f);
	snprintf(want, sizeof(want), "%-8s", key);
	for (at = 0; at + 80 <= n; at += 80)
		if (memcmp(head + at, want, 8) == 0 && head[at + 8] == '=')
			break;
	assert_true(at + 80 <= n);
	snprintf(card, sizeof(card), "%-8s= %20s%-50s", key, value, "");
	fseek(f, (long)at, SEEK_SET);
	fwrite(card, 1, 80, f);
	fclose(f);
}

/* Header card key (80 characters) of the FITS file at path. */
static void get_card(const char *path, const char *key, char card[81])
{
	char head[2880 * 4], want[9];
	FILE *f = fopen(path, "rb");
	size_t n, at;

	assert_non_null(f);
	n = fread(head, 1, sizeof(head), f);
	fclose(f);
	snprintf(want, sizeof(want), "%-8s", key);
	for (at = 0; at + 80 <= n; at += 80)
		if (memcmp(head + at, want, 8) == 0)
			break;
	assert_true(at + 80 <= n);
	memcpy(card, head + at, 80);
	card[80] = '\0';
}

/* A FITS file of the given cards (each up to 80 characters), END, the
 * header padded to 2880 bytes, then data_bytes of zeros. */
static void fits_file(const char *path, const char *const *cards,
		      size_t data_bytes)
{
	char block[2880];
	FILE *f = fopen(path, "wb");
	size_t i, at = 0;

	assert_non_null(f);
	memset(block, ' ', sizeof(block));
	for (i = 0; cards[i]; i++, at += 80) {
		assert_true(at + 80 < sizeof(block));
		memcpy(block + at, cards[i], strlen(cards[i]));
	}
	memcpy(block + at, "END", 3);
	fwrite(block, 1, sizeof(block), f);
	memset(block, 0, sizeof(block));
	for (; data_bytes > 0; data_bytes -= data_bytes < 2880 ? data_bytes
								: 2880)
		fwrite(block, 1, data_bytes < 2880 ? data_bytes : 2880, f);
	fclose(f);
}

static int setup(void **state)
{
	(void)state;
	if (cli_setup("h2fits"))
		return -1;
	return 0;
}

static int teardown(void **state)
{
	(void)state;
	return cli_teardown();
}

/* Four 768 x 768 flight frames of the truth generator (dir/fl, with
 * dir/fl.aem and the model dir/weak.csv), copied to dir/name. */
static char *flight(const char *name)
{
	static int made;
	char *copy = in_dir(name);

	if (!made) {
		FILE *f = fopen(in_dir("weak.csv"), "w");

		assert_non_null(f);
		fputs("theta_deg,alpha\n0,1\n30,1e-6\n60,1e-7\n90,1e-8\n", f);
		fclose(f);
		sh(MAKE_FLIGHT " '%s' '%s' '%s' 1 4 768 30 60", in_dir("fl"),
		   in_dir("fl.aem"), in_dir("weak.csv"));
		made = 1;
	}
	sh("rm -rf '%s' && cp -a '%s' '%s'", copy, in_dir("fl"), copy);
	return copy;
}

static int flightcheck(const char *folder)
{
	return STRAY("flightcheck", (char *)folder, "--aem", in_dir("fl.aem"),
		     "--model", in_dir("weak.csv"), "--json");
}

/* Defect 1: a row `frame(OUT)` made cfitsio write a copy to OUT (any
 * path), `frame[pix X*0+4095]` rewrote the pixels, both exit 0. */
static void test_manifest_names_are_names(void **state)
{
	char row[400], *f;

	(void)state;
	f = flight("paren");
	snprintf(row, sizeof(row), FRAME(3) "(%s)", in_dir("written.fits"));
	edit_row(f, 5, row, NULL, 0);
	flightcheck(f);
	expect_bad("manifest.csv:5: file");
	assert_false(exists(in_dir("written.fits")));

	f = flight("pix");
	edit_row(f, 5, FRAME(3) "[pix X*0+4095]", NULL, 0);
	flightcheck(f);
	expect_bad(FRAME(3) "[pix X*0+4095]");

	f = flight("dotdot");
	edit_row(f, 5, "..", NULL, 0);
	flightcheck(f);
	expect_bad("manifest.csv:5: file");
}

/* Defect 1: a listed symlink (leaving the folder) was followed, a
 * listed FIFO hung flightcheck. */
static void test_listed_symlink_and_fifo(void **state)
{
	char *f;

	(void)state;
	f = flight("link");
	sh("mv '%s/" FRAME(3) "' '%s' && ln -s '%s' '%s/" FRAME(3) "'", f,
	   in_dir("outside.fits"), in_dir("outside.fits"), f);
	flightcheck(f);
	expect_bad("manifest.csv:5: file '" FRAME(3) "': is a symbolic link");

	f = flight("fifo");
	sh("rm '%s/" FRAME(3) "' && mkfifo '%s/" FRAME(3) "'", f, f);
	flightcheck(f);
	expect_bad("manifest.csv:5: file '" FRAME(3) "': is not a regular");
}

/* Defect 3: a 6 KB first frame claiming 65536 x 8192 pixels took
 * 1.1 GB before "out of memory" (exit 1). */
static void test_frame_size_held_to_file(void **state)
{
	static char date[81];
	static const char *const cards[] = {
		"SIMPLE  =                    T",
		"BITPIX  =                   16",
		"NAXIS   =                    2",
		"NAXIS1  =                65536",
		"NAXIS2  =                 8192",
		"BZERO   =                32768",
		"FRAMETYP= 'FULL    '",
		"ANGLE   =                  0.0",
		"EXPTIME =                  0.1",
		"NDTRANS =                  1.0",
		"SEQNUM  =                    0",
		"SATLEVEL=                65535",
		date,		/* the frame's own: inside the AEM */
		NULL
	};
	char *f, *frame;

	(void)state;
	f = flight("huge");
	frame = in_dir("huge/" FRAME(0));
	get_card(frame, "DATE-OBS", date);
	fits_file(frame, cards, 3000);
	edit_row(f, 2, NULL, NULL, 1);
	flightcheck(f);
	expect_bad(FRAME(0) ": NAXIS1 x NAXIS2");
}

static double alpha_at(const char *json, int k)
{
	cJSON *j = cJSON_Parse(json), *p;
	double a;

	assert_non_null(j);
	p = cJSON_GetArrayItem(cJSON_GetObjectItem(j, "per_frame"), k);
	assert_non_null(p);
	a = cJSON_GetObjectItem(p, "alpha_px")->valuedouble;
	cJSON_Delete(j);
	return a;
}

/* Defect 4: flightcheck checked no SHA-256 and used the sensor's
 * exposure for every frame, whatever its EXPTIME. */
static void test_flightcheck_hashes_and_exptime(void **state)
{
	char *f;
	double a0, a1;
	FILE *fp;

	(void)state;
	f = flight("base");
	flightcheck(f);
	expect_ok();
	a0 = alpha_at(r.out, 1);

	/* a changed byte in the data: the manifest's hash disagrees */
	f = flight("hash");
	fp = fopen(in_dir("hash/" FRAME(2)), "r+b");
	assert_non_null(fp);
	fseek(fp, 2880 * 3 + 1001, SEEK_SET);
	fputc(0x55, fp);
	fclose(fp);
	flightcheck(f);
	expect_bad(FRAME(2));
	assert_non_null(strstr(r.err, "sha256 '"));

	/* the header's EXPTIME must be the manifest's */
	f = flight("expmis");
	set_card(in_dir("expmis/" FRAME(1)), "EXPTIME", "0.2");
	edit_row(f, 3, NULL, NULL, 1);
	flightcheck(f);
	expect_bad(FRAME(1) ": EXPTIME");

	/* frame 1 exposed twice as long, the same counts: half the light */
	f = flight("exp2");
	set_card(in_dir("exp2/" FRAME(1)), "EXPTIME", "0.2");
	edit_row(f, 3, NULL, "0.200000", 1);
	flightcheck(f);
	expect_ok();
	a1 = alpha_at(r.out, 1);
	if (!(fabs(a1 / a0 - 0.5) < 0.05))
		fail_msg("alpha_px %g at EXPTIME 0.2, %g at 0.1: want half", a1,
			 a0);
}

/* Defect 5: a duplicated row was blamed on the output file. */
static void test_duplicate_row_named(void **state)
{
	char path[300], *f;
	FILE *fp;

	(void)state;
	f = flight("dup");
	snprintf(path, sizeof(path), "%s/manifest.csv", f);
	fp = fopen(path, "a");
	assert_non_null(fp);
	fputs(FRAME(3) ",FULL,0.0000,0.100000,1,3,"
	      "0000000000000000000000000000000000000000000000000000000000000000"
	      "\n", fp);
	fclose(fp);
	STRAY("flightcheck", f, "--aem", in_dir("fl.aem"), "--model",
	      in_dir("weak.csv"), "--out", in_dir("fc.csv"));
	expect_bad("manifest.csv:6: file '" FRAME(3) "': is listed twice");
	assert_false(exists(in_dir("fc.csv")));
}

/* Only the names asked for in dir/sub (and nothing else). */
static int entries(const char *sub)
{
	DIR *d = opendir(in_dir(sub));
	struct dirent *e;
	int n = 0;

	assert_non_null(d);
	while ((e = readdir(d)) != NULL)
		n += e->d_name[0] != '.';
	closedir(d);
	return n;
}

/* Defect 1 (outputs): 'map[compress].fits' wrote 'map', 'map (1).fits'
 * and an --out-dir 'my frames (1)' failed and left 2880-byte pieces. */
static void test_output_paths_are_literal(void **state)
{
	(void)state;
	mkdir(in_dir("out"), 0700);
	STRAY("trace", "--scene", "ref4", "--angles", "40", "--rays", "2000",
	      "--set", "segments=64", "--focal-map",
	      in_dir("out/map[compress].fits"), "--map-angle", "40");
	expect_ok();
	STRAY("trace", "--scene", "ref4", "--angles", "40", "--rays", "2000",
	      "--set", "segments=64", "--focal-map", in_dir("out/map (1).fits"),
	      "--map-angle", "40");
	expect_ok();
	assert_true(exists(in_dir("out/map[compress].fits")));
	assert_true(exists(in_dir("out/map (1).fits")));
	assert_int_equal(entries("out"), 2);
	/* and read back by its name */
	STRAY("frames", "--alpha", "3e-7", "--window", "64", "--frames", "1",
	      "--map", in_dir("out/map (1).fits"));
	expect_ok();

	mkdir(in_dir("fr"), 0700);
	STRAY("frames", "--alpha", "3e-7", "--window", "64", "--frames", "2",
	      "--out-dir", in_dir("fr/my frames (1)"));
	expect_ok();
	assert_true(exists(in_dir("fr/my frames (1)/manifest.csv")));
	assert_true(exists(in_dir("fr/my frames (1)/" FRAME(1))));
	assert_int_equal(entries("fr"), 1);
}

/* Defect 2: a 5.7 KB map claiming 2^32 x 2^30 cells (the product wraps
 * to 0 before the allocation) crashed `stray frames --map`; a FIFO as
 * the map hung it. */
static void test_focal_map_size_held_to_file(void **state)
{
	static const char *const cards[] = {
		"SIMPLE  =                    T",
		"BITPIX  =                  -32",
		"NAXIS   =                    2",
		"NAXIS1  =           4294967296",
		"NAXIS2  =           1073741824",
		NULL
	};
	char *map = in_dir("huge_map.fits");

	(void)state;
	fits_file(map, cards, 2880);
	STRAY("frames", "--alpha", "3e-7", "--window", "64", "--frames", "1",
	      "--map", map);
	expect_bad("huge_map.fits: NAXIS1 x NAXIS2");

	map = in_dir("map_fifo.fits");
	assert_int_equal(mkfifo(map, 0600), 0);
	STRAY("frames", "--alpha", "3e-7", "--window", "64", "--frames", "1",
	      "--map", map);
	expect_bad("map_fifo.fits: is not a regular file");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_manifest_names_are_names),
		cmocka_unit_test(test_listed_symlink_and_fifo),
		cmocka_unit_test(test_frame_size_held_to_file),
		cmocka_unit_test(test_flightcheck_hashes_and_exptime),
		cmocka_unit_test(test_duplicate_row_named),
		cmocka_unit_test(test_output_paths_are_literal),
		cmocka_unit_test(test_focal_map_size_held_to_file),
	};

	(void)run_stray;	/* run_limited: a child may hang or grow */
	return cmocka_run_group_tests(tests, setup, teardown);
}
