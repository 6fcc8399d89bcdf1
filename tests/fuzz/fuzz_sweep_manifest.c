/*
 * fuzz_sweep_manifest.c - libFuzzer target for the sweep manifest reader
 * (manifest.csv of a rig sweep, read by `stray reduce` and by `strayrigd`
 * on resume): it must fail cleanly or give rows inside their documented
 * ranges.  fuzz_reduce_input covers it too, sharing its time with FITS.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sweep_store.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_sweep_manifest m;
	struct stray_error err;
	char line[1024];
	size_t i;

	stray_error_clear(&err);
	if (stray_sweep_manifest_parse("manifest.csv", (const char *)data,
				       size, &m, &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	for (i = 0; i < m.n; i++)
		if (!(m.e[i].exptime_s > 0.0 && m.e[i].ndtrans > 0.0 &&
		      m.e[i].ndtrans <= 1.0 && fabs(m.e[i].angle_deg) <= 180.0 &&
		      strlen(m.e[i].sha256) == 64 && m.e[i].file[0] != '/'))
			__builtin_trap();
	stray_sweep_manifest_free(&m);
	return 0;
}
