/*
 * fuzz_starcat.c - libFuzzer target for the star catalogue readers
 * (stray/starcat.h: hip2.dat, hip_main.dat, BSC5, CSV): arbitrary bytes
 * parsed; a catalogue that parses is searched in a cone at two epochs and
 * its colours taken through a flat passband.
 */
#include <stddef.h>
#include <stdint.h>

#include "stray/colour.h"
#include "stray/errfmt.h"
#include "stray/starcat.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct stray_cat_star out[64];
	static const double wl[2] = { 300.0, 1100.0 }, one[2] = { 1.0, 1.0 };
	static const double dir[3] = { 0.0, 0.0, 1.0 };
	struct stray_spectrum flat = { 2, wl, one };
	struct stray_starcat c;
	static struct stray_colour col;
	static int have_col = -1;	/* the table once: it is the slow part */
	struct stray_error err;
	char line[1024];
	size_t n;

	stray_error_clear(&err);
	if (stray_starcat_parse((const char *)data, size, "fuzz.cat", &c, &err) !=
	    STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	stray_starcat_cone(&c, 2026.5, dir, 180.0, 99.0, out, 64, &n);
	stray_starcat_cone(&c, 1000.0, dir, 10.0, 8.0, out, 64, &n);
	if (have_col < 0)
		have_col = stray_colour_init(&col, &flat, &flat, &err) == STRAY_OK;
	if (have_col)
		stray_colour_apply(&col, out, n);
	stray_starcat_free(&c);
	return 0;
}
