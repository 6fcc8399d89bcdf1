/*
 * vec.h - float 3-vectors and the attitude quaternion (single precision).
 */
#ifndef FDRFW_VEC_H
#define FDRFW_VEC_H

float fdrfw_dot(const float a[3], const float b[3]);
float fdrfw_norm(const float a[3]);
void fdrfw_cross(const float a[3], const float b[3], float out[3]);

/* out = a / |a|; returns 0 when |a| is zero or not finite. */
int fdrfw_unit(const float a[3], float out[3]);

/* Angle between two vectors [deg] by atan2(|a x b|, a.b): accurate at 0. */
float fdrfw_angle_deg(const float a[3], const float b[3]);

/*
 * The boresight (+z of the sensor) in the inertial frame for the attitude
 * quaternion q = (w, x, y, z), Hamilton convention, rotating inertial
 * vectors into the sensor frame: v_s = R(q) v_i.  Then b = R(q)^T e_z,
 * the third row of R(q).
 */
void fdrfw_boresight(const float q[4], float b[3]);

/* The same for a quaternion only near unit length (an input within its
 * tolerance): renormalised first, in this function's own frame so the
 * copy is off the caller's deeper call paths. */
void fdrfw_boresight_renorm(const float q[4], float b[3]);

#endif /* FDRFW_VEC_H */
