/*
 * fuzz_curve_csv.c - libFuzzer target for the CSV readers: the table
 * parser and the attenuation-curve loader on arbitrary bytes, then the
 * exclusion search on whatever curve survives validation.
 */
#include <stddef.h>
#include <stdint.h>

#include "stray/curve_io.h"
#include "stray/errfmt.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_curve c;
	struct stray_error err;
	char line[1024];
	double theta;

	stray_error_clear(&err);
	if (stray_curve_parse("fuzz.csv", (const char *)data, size, &c,
			      &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	{
		struct stray_curve_view v = stray_curve_view_of(&c);

		stray_curve_alpha_at(&v, 17.0);
		stray_exclusion_angle(&v, 1e-6, &theta, &err);
	}
	stray_curve_free(&c);
	return 0;
}
