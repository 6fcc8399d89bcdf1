/*
 * angles.h - source-angle lists of `stray trace --angles LIST`:
 * comma-separated values and start:stop:step ranges (stop included),
 * e.g. "0,5,10:30:0.5"; sorted, duplicates merged.
 */
#ifndef TRACER_ANGLES_H
#define TRACER_ANGLES_H

#include <stddef.h>

#include "stray/error.h"

#define TRACER_ANGLES_MAX 100000
/* The default sweep: 0-30 deg every 5, 30-90 deg every 0.5 (issue 3). */
#define TRACER_ANGLES_DEFAULT "0:30:5,30:90:0.5"

/* Parse into a new array (free it); errors name the offending item. */
int tracer_angles_parse(const char *list, double **theta_deg, size_t *n,
			struct stray_error *err);

#endif /* TRACER_ANGLES_H */
