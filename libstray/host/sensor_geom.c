/*
 * sensor_geom.c - the ideal lens of a sensor (sensor_geom.h).
 */
#include <math.h>

#include "stray/sensor_geom.h"

#define PI 3.14159265358979323846

double stray_sensor_focal_length_mm(const struct stray_sensor *s)
{
	double pitch_mm = s->pixel_pitch_um * 1e-3;
	double half_w_mm = 0.5 * s->pixels_x * pitch_mm;
	double half_h_mm = 0.5 * s->pixels_y * pitch_mm;

	return hypot(half_w_mm, half_h_mm) / tan(s->fov_half_deg * PI / 180.0);
}

double stray_sensor_pixel_deg(const struct stray_sensor *s)
{
	return s->pixel_pitch_um * 1e-3 / stray_sensor_focal_length_mm(s) *
	       180.0 / PI;
}
