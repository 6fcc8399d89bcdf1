/*
 * fuzz_flight_frame.c - libFuzzer target for a flight frame as `stray
 * flightcheck` reads it (tools/flightcheck_run.c): the lab-frame header
 * and its checks from memory (stray_sweep_fits_open_mem), DATE-OBS as a
 * UTC epoch, the pixels.  A header's NAXIS must never claim more pixels
 * than the bytes hold (issue 31: a 6 KB frame claiming 65536 x 8192 took
 * 1.1 GB), so the pixels are always read, into a buffer of that size.
 */
#include <fitsio.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

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
