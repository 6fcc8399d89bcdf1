/*
 * fuzz_import_frame.c - libFuzzer target for a frame written by other
 * software as `stray sweep import` reads it (libstray/sweep/import_frame.c,
 * import_tiff.c): FITS through cfitsio, TIFF through libtiff, both from
 * memory.  It must fail cleanly or give an image inside the store's
 * limits whose pixels can all be read.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sweep_import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_import_header h;
	struct stray_sweep_buf b;
	struct stray_error err;
	size_t pad = (size + 2879) / 2880 * 2880, i;
	unsigned sum = 0;
	uint16_t *px = NULL;
	char line[1024];

	/* as stray_sweep_file_load leaves it: zeros to a whole FITS block */
	b.cap = pad ? pad : 2880;
	b.data = calloc(1, b.cap);
	b.len = size;
	if (!b.data)
		return 0;
	memcpy(b.data, data, size);
	stray_error_clear(&err);
	if (stray_import_frame_read("frame", &b, &h, &px, &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
	} else {
		if (h.n_rows < 1 || h.n_rows > STRAY_SWEEP_ROWS_MAX ||
		    h.n_cols < 1 || h.n_cols > STRAY_SWEEP_COLS_MAX || !px)
			__builtin_trap();
		for (i = 0; i < h.n_rows * h.n_cols; i++)
			sum += px[i];	/* every pixel there (ASan) */
		(void)sum;
	}
	free(px);
	free(b.data);
	return 0;
}
