/*
 * test_sweep_manifest.c - manifest.csv (docs/formats.md) through libcsv
 * and the frames' SHA-256 through OpenSSL: good rows in any column order,
 * and one clear error naming line and column for each bad one.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/sweep_store.h"
#include "test_util.h"

#define HDR "file,frametyp,angle_deg,exptime_s,ndtrans,seqnum,sha256\n"
#define SHA_TAIL \
	"a7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
#define SHA "b" SHA_TAIL

static int parse(const char *text, struct stray_sweep_manifest *m,
		 struct stray_error *err)
{
	stray_error_clear(err);
	return stray_sweep_manifest_parse("manifest.csv", text, strlen(text), m,
					  err);
}

static void test_manifest_good_rows(void **state)
{
	struct stray_sweep_manifest m;
	struct stray_error err;
	const char *text =
		"# sweep 2026-11-20\n"
		"seqnum,sha256,file,frametyp,exptime_s,ndtrans,angle_deg,note\n"
		"0," SHA ",d0.fits,DARK,0.1,1,0,x\n"
		"\n"
		"2," SHA ",\"f 1.fits\",FULL,0.5,0.01,-12.5,\"a,b\"\r\n";

	(void)state;
	assert_int_equal(parse(text, &m, &err), STRAY_OK);
	assert_int_equal(m.n, 2);
	assert_string_equal(m.e[1].file, "f 1.fits");
	assert_int_equal(m.e[1].type, STRAY_SWEEP_FULL);
	assert_near(m.e[1].angle_deg, -12.5, 0);
	assert_near(m.e[1].ndtrans, 0.01, 0);
	assert_int_equal(m.e[1].seqnum, 2);
	assert_int_equal(m.e[1].line, 5);
	assert_string_equal(m.e[0].sha256, SHA);
	stray_sweep_manifest_free(&m);
}

/* Each bad manifest: the status, the line and the column named. */
static void expect(const char *text, int code, long line, const char *field)
{
	struct stray_sweep_manifest m;
	struct stray_error err;
	char msg[512];

	assert_int_equal(parse(text, &m, &err), code);
	print_message("%s\n", stray_error_format(&err, msg, sizeof(msg)));
	assert_int_equal(err.line, line);
	assert_string_equal(err.field, field);
	assert_null(m.e);
}

static void test_manifest_bad_rows(void **state)
{
	(void)state;
	expect("file,frametyp,angle_deg,exptime_s,ndtrans,seqnum\n",
	       STRAY_ENOTFOUND, 1, "sha256");
	expect(HDR "a.fits,BIAS,0,0.1,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "frametyp");
	expect(HDR "a.fits,FULL,nan,0.1,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "angle_deg");
	expect(HDR "a.fits,FULL,200,0.1,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "angle_deg");
	expect(HDR "a.fits,FULL,1,0,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "exptime_s");
	expect(HDR "a.fits,FULL,1,0.1,1.5,0," SHA "\n", STRAY_EPARSE, 2,
	       "ndtrans");
	expect(HDR "a.fits,FULL,1,0.1,1,1.5," SHA "\n", STRAY_EPARSE, 2,
	       "seqnum");
	expect(HDR "a.fits,FULL,1,0.1,1,0,abc\n", STRAY_EPARSE, 2, "sha256");
	expect(HDR "../a.fits,FULL,1,0.1,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "file");
	expect(HDR "a.fits,FULL,1\n", STRAY_EPARSE, 2, "row");
	expect(HDR "\"a.fits,FULL,1,0.1,1,0," SHA "\n", STRAY_EPARSE, 2, "csv");
	expect(HDR, STRAY_EPARSE, 1, "file");	/* no frames */
}

/* Issue 31: names are plain names of the folder (opened as given, never
 * through cfitsio's syntax), a file listed twice is named at its second
 * row. */
static void test_manifest_plain_names_once(void **state)
{
	(void)state;
	expect(HDR "sub/a.fits,FULL,1,0.1,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "file");
	expect(HDR "a.fits(/tmp/x.fits),FULL,1,0.1,1,0," SHA "\n",
	       STRAY_EPARSE, 2, "file");
	expect(HDR "..,FULL,1,0.1,1,0," SHA "\n", STRAY_EPARSE, 2, "file");
	expect(HDR ".,FULL,1,0.1,1,0," SHA "\n", STRAY_EPARSE, 2, "file");
	expect(HDR "\"a\tb.fits\",FULL,1,0.1,1,0," SHA "\n", STRAY_EPARSE, 2,
	       "file");
	expect(HDR "a.fits,FULL,1,0.1,1,0," SHA "\n"
	       "b.fits,FULL,1,0.1,1,1," SHA "\n"
	       "a.fits,FULL,1,0.1,1,2," SHA "\n", STRAY_EPARSE, 4, "file");
}

/* FIPS 180-2 appendix B.1: SHA-256("abc"). */
static void test_manifest_sha256_vector(void **state)
{
	char path[] = "/tmp/stray_sha_XXXXXX";
	struct stray_error err;
	int fd = mkstemp(path);

	(void)state;
	assert_true(fd >= 0);
	assert_int_equal(write(fd, "abc", 3), 3);
	close(fd);
	stray_error_clear(&err);
	assert_int_equal(stray_sweep_sha256_check(path, SHA, &err), STRAY_OK);
	/* one digit changed: "ba78..." -> "ca78..." */
	assert_int_equal(stray_sweep_sha256_check(path, "c" SHA_TAIL, &err),
			 STRAY_EINVAL);
	assert_string_equal(err.field, "sha256");
	assert_string_equal(err.text, SHA);
	unlink(path);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_manifest_good_rows),
		cmocka_unit_test(test_manifest_bad_rows),
		cmocka_unit_test(test_manifest_plain_names_once),
		cmocka_unit_test(test_manifest_sha256_vector),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
