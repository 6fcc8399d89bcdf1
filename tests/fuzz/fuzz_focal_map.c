/*
 * fuzz_focal_map.c - libFuzzer target for the focal-map reader of
 * `stray frames --map` and `stray flightcheck` (frames/focal_map_read.c):
 * the bytes as a FITS file on disk, read with its size checks (issue 31:
 * a 5.7 KB map claiming 2^32 x 2^30 cells overflowed the heap), then
 * resampled to a small window.  Any map must fail cleanly or give cells
 * that are finite and >= 0 and fit the file.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "frames/focal_map_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static char path[64];
	struct focal_map_file m;
	struct stray_error err;
	float out[16 * 12];
	FILE *f;
	size_t i;
	int rc;

	if (!path[0])
		snprintf(path, sizeof(path), "/tmp/fuzz_focal_map_%d.fits",
			 (int)getpid());
	f = fopen(path, "wb");
	if (!f)
		return 0;
	fwrite(data, 1, size, f);
	fclose(f);
	stray_error_clear(&err);
	rc = focal_map_load(path, &m, &err);
	unlink(path);
	if (rc == 0) {
		/* four bytes a cell at least (BITPIX 32 or -32; 8 and 16 read
		 * as fewer): never more cells than the bytes could hold */
		if (!(m.nx >= 1 && m.ny >= 1 &&
		      (size_t)m.nx * (size_t)m.ny <= size))
			__builtin_trap();
		for (i = 0; i < (size_t)m.nx * (size_t)m.ny; i++)
			if (!(isfinite(m.cell[i]) && m.cell[i] >= 0.0f))
				__builtin_trap();
		focal_map_resample(&m, 64, 48, 8, 4, 16, 12, 1.0, out);
		for (i = 0; i < sizeof(out) / sizeof(out[0]); i++)
			if (!(out[i] >= 0.0f))
				__builtin_trap();
		focal_map_file_free(&m);
	}
	return 0;
}
