/*
 * sampling.c - the warps the tracer shares, each beside its pdf.
 */
#include <math.h>

#include "tracer/brdf.h"

void tracer_sample_disk(double u1, double u2, double *x, double *y)
{
	/* Concentric map (Shirley and Chiu 1997, J. Graphics Tools 2(3)):
	 * area-preserving and continuous, so stratification survives. */
	double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
	double r, phi;

	if (a == 0.0 && b == 0.0) {
		*x = *y = 0.0;
		return;
	}
	if (fabs(a) > fabs(b)) {
		r = a;
		phi = (M_PI / 4.0) * (b / a);
	} else {
		r = b;
		phi = M_PI / 2.0 - (M_PI / 4.0) * (a / b);
	}
	*x = r * cos(phi);
	*y = r * sin(phi);
}

void tracer_sample_disk_inverse(double x, double y, double *u1, double *u2)
{
	/* The concentric map's four wedges undone: r and phi from (x, y),
	 * then the square's (a, b) of that wedge. */
	double r = sqrt(x * x + y * y), phi = atan2(y, x), a, b;

	if (phi < -M_PI / 4.0)
		phi += 2.0 * M_PI;	/* phi in [-pi/4, 7 pi/4) */
	if (phi < M_PI / 4.0) {
		a = r;
		b = r * phi * (4.0 / M_PI);
	} else if (phi < 3.0 * M_PI / 4.0) {
		b = r;
		a = r * (M_PI / 2.0 - phi) * (4.0 / M_PI);
	} else if (phi < 5.0 * M_PI / 4.0) {
		a = -r;
		b = -r * (phi - M_PI) * (4.0 / M_PI);
	} else {
		b = -r;
		a = -r * (M_PI / 2.0 - (phi - M_PI)) * (4.0 / M_PI);
	}
	*u1 = 0.5 * (a + 1.0);
	*u2 = 0.5 * (b + 1.0);
}

struct vec3 tracer_sample_cosine_hemisphere(double u1, double u2)
{
	/* Malley's method: a uniform disk point lifted to the hemisphere. */
	double x, y, z2;

	tracer_sample_disk(u1, u2, &x, &y);
	z2 = 1.0 - x * x - y * y;
	return v3(x, y, z2 > 0.0 ? sqrt(z2) : 0.0);
}

double tracer_cosine_hemisphere_pdf(double cos_theta)
{
	return cos_theta > 0.0 ? cos_theta / M_PI : 0.0;
}
