/*
 * angles.h - source-angle lists of `stray trace --angles LIST`:
 * comma-separated values and start:stop:step ranges (stop included),
 * e.g. "0,5,10:30:0.5"; sorted, duplicates merged.
 */
#ifndef TRACER_ANGLES_H
#define TRACER_ANGLES_H

#include <stddef.h>

#include "stray/error.h"

struct tracer_scene;

#define TRACER_ANGLES_MAX 100000
/* The fixed sweep of issue 3: 0-30 deg every 5, 30-90 deg every 0.5.
 * `stray trace` without --angles uses tracer_angles_auto instead. */
#define TRACER_ANGLES_DEFAULT "0:30:5,30:90:0.5"

/* Parse into a new array (free it); errors name the offending item. */
int tracer_angles_parse(const char *list, double **theta_deg, size_t *n,
			struct stray_error *err);

/* 0 put first in *theta_deg (an array of *n from the above) when it is
 * not there: alpha is normalised to P(0).  *added says whether it was. */
int tracer_angles_with_zero(double **theta_deg, size_t *n, int *added,
			    struct stray_error *err);

/*
 * The default grid fitted to a committed scene (angles_auto.c): the
 * direct cut-off found by shadow rays on a 0.1 deg lattice (*cutoff_deg:
 * where the last unobstructed source ray to the detector ends; 0 when
 * none reaches it on axis), then 1 deg steps below it, 0.1 deg within
 * 1 deg of it and 0.5 deg beyond, to 90 deg.  A superset of
 * TRACER_ANGLES_DEFAULT.  New array in *theta_deg (free it).
 */
int tracer_angles_auto(const struct tracer_scene *s, double **theta_deg,
		       size_t *n, double *cutoff_deg, struct stray_error *err);

#endif /* TRACER_ANGLES_H */
