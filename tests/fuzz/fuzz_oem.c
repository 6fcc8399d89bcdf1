/*
 * fuzz_oem.c - libFuzzer target for the CCSDS OEM reader: arbitrary bytes
 * parsed, and a message that parses interpolated across its span.
 */
#include <stddef.h>
#include <stdint.h>

#include "stray/errfmt.h"
#include "stray/oem.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_oem o;
	struct stray_error err;
	char line[1024];
	int k;

	stray_error_clear(&err);
	if (stray_oem_parse((const char *)data, size, "fuzz.oem", &o, &err) !=
	    STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	for (k = 0; k <= 8; k++) {
		double r[3], v[3];

		stray_oem_state(&o, o.cover.t0 + (o.cover.t1 - o.cover.t0) * k / 8.0,
				r, v);
	}
	stray_oem_free(&o);
	return 0;
}
