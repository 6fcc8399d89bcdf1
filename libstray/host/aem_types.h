/*
 * aem_types.h - the attitude types of an AEM (504.0-B-1 and B-2) to the
 * one rotation matrix the reader needs (private to libstray/host).
 */
#ifndef STRAY_AEM_TYPES_H
#define STRAY_AEM_TYPES_H

enum aem_type { AEM_QUATERNION, AEM_QUATERNION_DERIV, AEM_QUATERNION_RATE,
		AEM_EULER, AEM_EULER_RATE, AEM_SPIN, AEM_SPIN_NUTATION };

/* The type named by an ATTITUDE_TYPE value (either version's names,
 * any case); -1 if none. */
int aem_type(const char *value);

/* Numbers after the epoch on a data line of the type. */
int aem_type_fields(int type);

/* Quaternion types need QUATERNION_TYPE (version 1), Euler angle types
 * EULER_ROT_SEQ. */
int aem_type_is_quaternion(int type);
int aem_type_is_euler(int type);

/* EULER_ROT_SEQ as 1-2-3 digits (version 1) or X-Y-Z letters: axes
 * 0..2, consecutive ones different (the 12 sequences); 0, else -1. */
int aem_euler_seq(const char *value, int axis[3]);

/*
 * The matrix M taking frame-A coordinates to frame-B coordinates as the
 * data line x[] says (before ATTITUDE_DIR): quaternion q_c first or last
 * (normalised: *norm gets |q| for the caller's check), Euler angles in
 * degrees applied in the sequence's order (M = R_a3(x3) R_a2(x2)
 * R_a1(x1), frame rotations, as Orekit's FRAME_TRANSFORM), spin
 * (right ascension, declination of the spin axis, spin angle, deg: the
 * 3-1-3 rotation 90 + alpha, 90 - delta, phi).
 */
void aem_type_dcm(int type, const double *x, int q_first,
		  const int axis[3], double m[3][3], double *norm);

/* The frame rotation about axis (0 x, 1 y, 2 z) by a radians. */
void aem_axis_dcm(int axis, double a, double m[3][3]);

#endif /* STRAY_AEM_TYPES_H */
