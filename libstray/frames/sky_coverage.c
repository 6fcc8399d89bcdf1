/*
 * sky_coverage.c - the fraction of the sky with enough detectable stars
 * (sky_coverage.h).
 */
#include <math.h>
#include <stdlib.h>

#include "stray/sky_coverage.h"
#include "stray/catalogue.h"
#include "stray/sensor_geom.h"

#define CONE_MAX 20000		/* stars of one cone (m <= ~8 over 30 deg) */

/* A head frame whose +z is the boresight d (rows of m_ih: x, y, z). */
static void head_frame(const double d[3], double m[3][3])
{
	double a[3] = { 0.0, 0.0, 1.0 }, n;
	int i;

	if (fabs(d[2]) > 0.9) {
		a[0] = 1.0;
		a[2] = 0.0;
	}
	/* x = a x d normalised, y = d x x */
	m[0][0] = a[1] * d[2] - a[2] * d[1];
	m[0][1] = a[2] * d[0] - a[0] * d[2];
	m[0][2] = a[0] * d[1] - a[1] * d[0];
	n = sqrt(m[0][0] * m[0][0] + m[0][1] * m[0][1] + m[0][2] * m[0][2]);
	for (i = 0; i < 3; i++) {
		m[0][i] /= n;
		m[2][i] = d[i];
	}
	m[1][0] = d[1] * m[0][2] - d[2] * m[0][1];
	m[1][1] = d[2] * m[0][0] - d[0] * m[0][2];
	m[1][2] = d[0] * m[0][1] - d[1] * m[0][0];
}

int sky_coverage(const struct stray_sensor *s, double mag_lim, int n_min,
		 double *frac, struct stray_error *err)
{
	struct stray_cat_star *cat = malloc(CONE_MAX * sizeof(*cat));
	struct stray_camera cam;
	long ok = 0;
	int k;

	if (!cat)
		return stray_error_set(err, STRAY_ENOMEM, "sky_coverage",
				       "out of memory");
	cam.f_px = stray_sensor_focal_length_mm(s) / (s->pixel_pitch_um * 1e-3);
	cam.cx = 0.5 * s->pixels_x;
	cam.cy = 0.5 * s->pixels_y;
	for (k = 0; k < SKY_COVERAGE_DIRS; k++) {
		/* Fibonacci lattice: equal areas over the sphere */
		double z = 1.0 - (2.0 * k + 1.0) / SKY_COVERAGE_DIRS;
		double r = sqrt(1.0 - z * z), phi = k * 2.39996322972865332;
		double d[3] = { r * cos(phi), r * sin(phi), z }, x, y;
		size_t n = 0, i;
		int count = 0;

		head_frame(d, cam.m_ih);
		stray_catalogue_cone(STRAY_CATALOGUE_SEED, d, s->fov_half_deg,
				     mag_lim, cat, CONE_MAX, &n);
		for (i = 0; i < n && count < n_min; i++)
			if (stray_camera_project(&cam, cat[i].u, &x, &y) &&
			    x >= 0 && y >= 0 && x < s->pixels_x &&
			    y < s->pixels_y)
				count++;
		ok += count >= n_min;
	}
	free(cat);
	*frac = (double)ok / SKY_COVERAGE_DIRS;
	return STRAY_OK;
}
