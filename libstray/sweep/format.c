/*
 * format.c - the names of a sweep folder (sweep_store.h): frame types
 * and frame file names.
 */
#include <stdio.h>
#include <string.h>

#include "stray/sweep_store.h"

static const char *const type_names[STRAY_SWEEP_FRAMETYP_COUNT] = {
	"DARK", "AMBIENT", "FULL"
};

int stray_sweep_frametyp_parse(const char *text)
{
	int t;

	for (t = 0; t < STRAY_SWEEP_FRAMETYP_COUNT; t++)
		if (strcmp(text, type_names[t]) == 0)
			return t;
	return -1;
}

const char *stray_sweep_frametyp_name(int type)
{
	return type >= 0 && type < STRAY_SWEEP_FRAMETYP_COUNT
		? type_names[type] : "?";
}

void stray_sweep_frame_filename(const struct stray_sweep_frame *f,
				char *out, size_t size)
{
	snprintf(out, size, "a%+08.3f_%s_%03ld.fits", f->angle_deg,
		 stray_sweep_frametyp_name(f->type), f->seqnum);
}
