/*
 * fuzz_import_log.c - libFuzzer target for the lab's log of `stray sweep
 * import` (libstray/sweep/import_log.c): it must fail cleanly or give
 * rows inside their documented ranges, one per file.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sweep_import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_import_log log;
	struct stray_error err;
	char line[1024];
	size_t i;

	stray_error_clear(&err);
	if (stray_import_log_parse("log.csv", (const char *)data, size, &log,
				   &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	for (i = 0; i < log.n; i++) {
		const struct stray_import_row *r = &log.r[i];

		if (!(r->exptime_s > 0.0 && isfinite(r->exptime_s) &&
		      r->ndtrans > 0.0 && r->ndtrans <= 1.0 &&
		      fabs(r->angle_deg) <= 180.0 && r->type >= 0 &&
		      r->type < STRAY_SWEEP_FRAMETYP_COUNT && r->file[0] &&
		      !strchr(r->file, '/') &&
		      (isnan(r->readback_deg) || fabs(r->readback_deg) <= 180.0) &&
		      (isnan(r->monitor) || r->monitor > 0.0) &&
		      strlen(r->filter) < STRAY_IMPORT_TEXT_MAX))
			__builtin_trap();
		if (i > 0 && strcmp(r->file, log.r[i - 1].file) == 0)
			__builtin_trap();	/* a file logged twice */
	}
	stray_import_log_free(&log);
	return 0;
}
