/*
 * sensor_geom.h - the sensor's ideal imaging geometry (hosted: libm's
 * tan and hypot, which the freestanding core does not link).  One place
 * for the focal length that the focal-plane maps (`stray trace
 * --focal-map`) and the rendered frames (`stray frames`) both use.
 */
#ifndef STRAY_SENSOR_GEOM_H
#define STRAY_SENSOR_GEOM_H

#include "stray/sensor.h"

/*
 * Focal length of the ideal lens [mm]: the field half-angle is the circle
 * that holds the detector, f = half-diagonal / tan(fov_half_deg).
 */
double stray_sensor_focal_length_mm(const struct stray_sensor *s);

/* Angle one pixel subtends on the axis [deg]: pitch / f. */
double stray_sensor_pixel_deg(const struct stray_sensor *s);

#endif /* STRAY_SENSOR_GEOM_H */
