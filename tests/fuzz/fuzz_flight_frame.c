/*
 * fuzz_flight_frame.c - libFuzzer target for a flight frame as `stray
 * flightcheck` reads it (mission/flightcheck_run.c): the lab-frame header
 * and its checks from memory (stray_sweep_fits_open_mem), DATE-OBS as a
 * UTC epoch, the pixels.  A header's NAXIS must never claim more pixels
 * than the bytes hold (issue 31: a 6 KB frame claiming 65536 x 8192 took
 * 1.1 GB), so the pixels are always read, into a buffer of that size.
 * The same bytes then as a camera's frame (issue 24: no lab keyword,
 * stray_sweep_fits_open_flight_buf).
 */
#include <fitsio.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "stray/ccsds.h"
#include "stray/sweep_store.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct stray_sweep_fits f;
	struct stray_error err;
	char v[FLEN_VALUE];
	double t;
	uint16_t *pix;
	int status = 0;

	stray_error_clear(&err);
	{	/* as a camera's frame: the buffer zero-padded to whole
		 * blocks, as stray_sweep_file_load leaves it */
		struct stray_sweep_buf b;

		b.len = size;
		b.cap = (size + 2879) / 2880 * 2880 + 2880;
		b.data = calloc(1, b.cap);
		if (b.data) {
			memcpy(b.data, data, size);
			if (stray_sweep_fits_open_flight_buf("fuzz.fits", &b, &f,
							     &err) == STRAY_OK) {
				if (!(f.h.exptime_s > 0.0 && f.h.n_rows >= 1 &&
				      2 * f.h.n_rows * f.h.n_cols <= size))
					__builtin_trap();
				pix = malloc(f.h.n_rows * f.h.n_cols * sizeof(*pix));
				if (pix)
					(void)stray_sweep_fits_read(&f, pix, &err);
				free(pix);
				stray_sweep_fits_close(&f);
			}
			free(b.data);
		}
	}
	if (stray_sweep_fits_open_mem("fuzz.fits", data, size, &f,
				      &err) != STRAY_OK)
		return 0;
	if (!(f.h.exptime_s > 0.0 && isfinite(f.h.exptime_s) &&
	      f.h.n_rows >= 1 && f.h.n_cols >= 1 &&
	      2 * f.h.n_rows * f.h.n_cols <= size))
		__builtin_trap();
	if (fits_read_key((fitsfile *)f.fptr, TSTRING, "DATE-OBS", v, NULL,
			  &status) == 0 &&
	    stray_ccsds_epoch(v, stray_ccsds_time_system("UTC"), &t) == 0 &&
	    !isfinite(t))
		__builtin_trap();
	fits_clear_errmsg();
	pix = malloc(f.h.n_rows * f.h.n_cols * sizeof(*pix));
	if (pix)
		(void)stray_sweep_fits_read(&f, pix, &err);
	free(pix);
	stray_sweep_fits_close(&f);
	return 0;
}
