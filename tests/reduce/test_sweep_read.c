/*
 * test_sweep_read.c - a frame read whole and decoded from memory (the
 * reduction's path: stray_sweep_file_load, stray_sweep_fits_open_buf)
 * gives the pixels cfitsio gives reading the file itself, for unsigned
 * 16-bit frames (the decoder's own loop) and signed ones (cfitsio's);
 * and the bytes hashed in memory hash as the file does.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <fitsio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/sweep_store.h"

#define ROWS 7
#define COLS 13
#define N (ROWS * COLS)

/* A frame with every keyword the store wants; bitpix USHORT_IMG or
 * SHORT_IMG (values then kept within 0..32767, as TUSHORT reads them). */
static void write_frame(const char *path, int bitpix, uint16_t *pix)
{
	fitsfile *f;
	long naxes[2] = { COLS, ROWS };
	int status = 0, i;
	double angle = 5.0, t = 0.1, nd = 1.0;
	long seq = 0, sat = 65535;

	for (i = 0; i < N; i++)	/* both ends of the range, and between */
		pix[i] = (uint16_t)(i == 0 ? 0 : i == 1 ? 65535 : i == 2 ?
				    32767 : i == 3 ? 32768 :
				    (unsigned)(i * 7919u) & 0xffffu);
	if (bitpix == SHORT_IMG)
		for (i = 0; i < N; i++)
			pix[i] &= 0x7fff;
	unlink(path);
	fits_create_file(&f, path, &status);
	fits_create_img(f, bitpix, 2, naxes, &status);
	fits_write_key(f, TSTRING, "FRAMETYP", "FULL", NULL, &status);
	fits_write_key(f, TDOUBLE, "ANGLE", &angle, NULL, &status);
	fits_write_key(f, TDOUBLE, "EXPTIME", &t, NULL, &status);
	fits_write_key(f, TDOUBLE, "NDTRANS", &nd, NULL, &status);
	fits_write_key(f, TLONG, "SEQNUM", &seq, NULL, &status);
	fits_write_key(f, TLONG, "SATLEVEL", &sat, NULL, &status);
	fits_write_img(f, TUSHORT, 1, N, pix, &status);
	fits_close_file(f, &status);
	assert_int_equal(status, 0);
}

static void read_both(const char *path, const uint16_t *want)
{
	struct stray_sweep_fits a, b;
	struct stray_sweep_buf buf = { 0 };
	struct stray_error err;
	uint16_t pa[N], pb[N];
	char h_file[STRAY_SWEEP_SHA256_HEX], h_mem[STRAY_SWEEP_SHA256_HEX];

	stray_error_clear(&err);
	assert_int_equal(stray_sweep_fits_open(path, &a, &err), STRAY_OK);
	assert_int_equal(stray_sweep_fits_read(&a, pa, &err), STRAY_OK);
	stray_sweep_fits_close(&a);
	assert_int_equal(stray_sweep_file_load(path, &buf, &err), STRAY_OK);
	assert_int_equal(buf.len % 2880, 0);
	assert_int_equal(stray_sweep_fits_open_buf(path, &buf, &b, &err),
			 STRAY_OK);
	assert_int_equal(stray_sweep_fits_read(&b, pb, &err), STRAY_OK);
	stray_sweep_fits_close(&b);
	assert_memory_equal(pa, want, sizeof(pa));
	assert_memory_equal(pb, want, sizeof(pb));
	assert_int_equal(stray_sweep_sha256_file(path, h_file, &err),
			 STRAY_OK);
	assert_int_equal(stray_sweep_sha256_mem(buf.data, buf.len, h_mem),
			 STRAY_OK);
	assert_string_equal(h_file, h_mem);
	assert_int_equal(stray_sweep_sha256_check_mem(path, buf.data, buf.len,
						      h_file, &err), STRAY_OK);
	h_file[0] = h_file[0] == '0' ? '1' : '0';
	assert_int_equal(stray_sweep_sha256_check_mem(path, buf.data, buf.len,
						      h_file, &err),
			 STRAY_EINVAL);
	stray_sweep_buf_free(&buf);
}

static void test_read_unsigned_from_memory(void **state)
{
	char path[] = "/tmp/stray_read_u16.fits";
	uint16_t pix[N];

	(void)state;
	write_frame(path, USHORT_IMG, pix);
	read_both(path, pix);
	unlink(path);
}

static void test_read_signed_from_memory(void **state)
{
	char path[] = "/tmp/stray_read_i16.fits";
	uint16_t pix[N];

	(void)state;
	write_frame(path, SHORT_IMG, pix);
	read_both(path, pix);
	unlink(path);
}

/* A file cut inside the data is short, whatever the zeros padding the
 * buffer to a whole block would say: refused at the open, before a
 * caller sizes a buffer by NAXIS (stray/sizes.h). */
static void test_read_truncated_from_memory(void **state)
{
	char path[] = "/tmp/stray_read_cut.fits";
	struct stray_sweep_fits f;
	struct stray_sweep_buf buf = { 0 };
	struct stray_error err;
	uint16_t pix[N];

	(void)state;
	write_frame(path, USHORT_IMG, pix);
	assert_int_equal(truncate(path, 2880 + 2 * N - 2), 0);
	stray_error_clear(&err);
	assert_int_equal(stray_sweep_file_load(path, &buf, &err), STRAY_OK);
	(void)pix;
	assert_int_equal(stray_sweep_fits_open_buf(path, &buf, &f, &err),
			 STRAY_EINVAL);
	assert_non_null(strstr(err.reason, "truncated"));
	assert_string_equal(err.field, "NAXIS1 x NAXIS2");
	stray_sweep_buf_free(&buf);
	unlink(path);
}

static void test_read_missing_file(void **state)
{
	struct stray_sweep_buf buf = { 0 };
	struct stray_error err;

	(void)state;
	stray_error_clear(&err);
	assert_int_equal(stray_sweep_file_load("/tmp/stray_no_such.fits", &buf,
					       &err), STRAY_ENOTFOUND);
	stray_sweep_buf_free(&buf);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_read_unsigned_from_memory),
		cmocka_unit_test(test_read_signed_from_memory),
		cmocka_unit_test(test_read_truncated_from_memory),
		cmocka_unit_test(test_read_missing_file),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
