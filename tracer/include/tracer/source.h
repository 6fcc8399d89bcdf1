/*
 * source.h - the collimated source of the baffle sweep (thesis §3.4,
 * ref4-baffle.md): a uniform beam from direction (0, sin theta, cos theta),
 * theta a rotation about +x through the entrance-aperture centre, filling
 * the entrance aperture (a disk of radius_mm across the beam).
 */
#ifndef TRACER_SOURCE_H
#define TRACER_SOURCE_H

#include <stdbool.h>

#include "tracer/vec.h"

struct tracer_beam {
	struct vec3 center;	/* entrance-aperture centre, mm */
	struct vec3 normal;	/* aperture normal, toward the source side */
	double radius_mm;	/* aperture radius */
};

/* Unit vector toward the source at off-axis angle theta_deg. */
struct vec3 tracer_source_dir(double theta_deg);

/*
 * True when the ray from p toward the source (direction d) crosses the
 * entrance-aperture disk: the beam is exactly the rays through it, so the
 * source lights p if nothing is in the way (no ray is spent outside the
 * projected aperture, whose area falls as cos theta).
 */
bool tracer_beam_covers(const struct tracer_beam *b, struct vec3 d,
			struct vec3 p);

#endif /* TRACER_SOURCE_H */
