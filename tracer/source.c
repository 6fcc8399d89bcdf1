/*
 * source.c - the collimated beam: direction and footprint.
 */
#include <math.h>

#include "tracer/source.h"

struct vec3 tracer_source_dir(double theta_deg)
{
	double t = theta_deg * (M_PI / 180.0);

	return v3(0.0, sin(t), cos(t));
}

bool tracer_beam_covers(const struct tracer_beam *b, struct vec3 d,
			struct vec3 p)
{
	double dn = v3_dot(d, b->normal), t;
	struct vec3 q;

	if (dn <= 0.0)
		return false;	/* the source is behind the aperture plane */
	t = v3_dot(v3_sub(b->center, p), b->normal) / dn;
	if (t < 0.0)
		return false;	/* p is outside, beyond the aperture */
	q = v3_sub(v3_add(p, v3_scale(d, t)), b->center);
	return v3_dot(q, q) <= b->radius_mm * b->radius_mm;
}
