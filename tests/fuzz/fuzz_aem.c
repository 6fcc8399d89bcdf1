/*
 * fuzz_aem.c - libFuzzer target for the CCSDS AEM reader: arbitrary bytes
 * parsed, and a message that parses interpolated (SLERP) across its span.
 */
#include <stddef.h>
#include <stdint.h>

#include "stray/aem.h"
#include "stray/errfmt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_aem a;
	struct stray_error err;
	char line[1024];
	int k;

	stray_error_clear(&err);
	if (stray_aem_parse((const char *)data, size, "fuzz.aem", &a, &err) !=
	    STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	for (k = 0; k <= 8; k++) {
		double q[4], m[3][3];

		stray_aem_attitude(&a, a.cover.t0 + (a.cover.t1 - a.cover.t0) * k / 8.0, q);
		stray_q_dcm(q, m);
	}
	stray_aem_free(&a);
	return 0;
}
