/*
 * fuzz_reduce_input.c - libFuzzer target for what `stray reduce` parses:
 * the first byte picks the manifest.csv parser (libcsv) or a FITS frame
 * header and pixels (cfitsio, from memory) with its ROWS list; either
 * must fail cleanly or give values inside their documented ranges.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "stray/sweep_store.h"

static void manifest(const uint8_t *data, size_t size)
{
	struct stray_sweep_manifest m;
	struct stray_error err;
	size_t i;

	stray_error_clear(&err);
	if (stray_sweep_manifest_parse("fuzz.csv", (const char *)data, size, &m,
				 &err) != STRAY_OK)
		return;
	for (i = 0; i < m.n; i++)
		if (!(m.e[i].exptime_s > 0.0 && m.e[i].ndtrans > 0.0 &&
		      m.e[i].ndtrans <= 1.0 && fabs(m.e[i].angle_deg) <= 180.0 &&
		      strlen(m.e[i].sha256) == 64 &&
		      !strchr(m.e[i].file, '/') && !strstr(m.e[i].file, "..")))
			__builtin_trap();
	stray_sweep_manifest_free(&m);
}

static void frame(const uint8_t *data, size_t size)
{
	static struct stray_sweep_fits f;
	struct stray_error err;
	uint16_t *pix;

	stray_error_clear(&err);
	if (stray_sweep_fits_open_mem("fuzz.fits", data, size, &f,
				      &err) == STRAY_OK) {
		/* the header checks, and NAXIS held to the bytes at the
		 * open (issue 31): the pixels always fit the input */
		if (!(f.h.exptime_s > 0.0 && f.h.ndtrans > 0.0 &&
		      f.h.ndtrans <= 1.0 && f.h.n_rows >= 1 &&
		      f.h.n_rows <= STRAY_SWEEP_ROWS_MAX &&
		      f.h.satlevel >= 1 && f.h.satlevel <= 65536 &&
		      2 * f.h.n_rows * f.h.n_cols <= size))
			__builtin_trap();
		pix = malloc(f.h.n_rows * f.h.n_cols * sizeof(*pix));
		if (pix)
			(void)stray_sweep_fits_read(&f, pix, &err);
		free(pix);
		stray_sweep_fits_close(&f);
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size == 0)
		return 0;
	if (data[0] & 1)
		frame(data + 1, size - 1);
	else
		manifest(data + 1, size - 1);
	return 0;
}
