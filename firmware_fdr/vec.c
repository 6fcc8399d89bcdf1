/*
 * vec.c - float 3-vectors and the attitude quaternion.
 */
#include <math.h>

#include "fdrfw/vec.h"

#define RAD_TO_DEG 57.29577951308232f

float fdrfw_dot(const float a[3], const float b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

float fdrfw_norm(const float a[3])
{
	return sqrtf(fdrfw_dot(a, a));
}

void fdrfw_cross(const float a[3], const float b[3], float out[3])
{
	float x = a[1] * b[2] - a[2] * b[1];
	float y = a[2] * b[0] - a[0] * b[2];
	float z = a[0] * b[1] - a[1] * b[0];

	out[0] = x;
	out[1] = y;
	out[2] = z;
}

int fdrfw_unit(const float a[3], float out[3])
{
	float n = fdrfw_norm(a);

	if (!(isfinite(n) && n > 0.0f))
		return 0;
	out[0] = a[0] / n;
	out[1] = a[1] / n;
	out[2] = a[2] / n;
	return 1;
}

float fdrfw_angle_deg(const float a[3], const float b[3])
{
	float c[3];

	fdrfw_cross(a, b, c);
	return atan2f(fdrfw_norm(c), fdrfw_dot(a, b)) * RAD_TO_DEG;
}

void fdrfw_boresight(const float q[4], float b[3])
{
	float w = q[0], x = q[1], y = q[2], z = q[3];

	/* Third row of the rotation matrix of a unit quaternion. */
	b[0] = 2.0f * (x * z - w * y);
	b[1] = 2.0f * (y * z + w * x);
	b[2] = 1.0f - 2.0f * (x * x + y * y);
}

void fdrfw_boresight_renorm(const float q[4], float b[3])
{
	float u[4];
	float n = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
	unsigned i;

	for (i = 0; i < 4u; i++)
		u[i] = q[i] / n;
	fdrfw_boresight(u, b);
}
