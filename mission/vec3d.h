/*
 * vec3d.h - the two 3-vector steps the mission writers and the heads file
 * build attitudes from (orbit.c, avail_demo.c, avail_heads.c).
 */
#ifndef STRAY_MISSION_VEC3D_H
#define STRAY_MISSION_VEC3D_H

#include <math.h>

/* a scaled to unit length in place. */
static inline void unit(double a[3])
{
	double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);

	a[0] /= n;
	a[1] /= n;
	a[2] /= n;
}

/* c = a x b */
static inline void cross(const double a[3], const double b[3], double c[3])
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

#endif /* STRAY_MISSION_VEC3D_H */
