/*
 * quaternion.h - attitude quaternions as CCSDS 504.0 means them (the AEM
 * reader's, stray/aem.h): q = (q_c, e1, e2, e3), their direction-cosine
 * matrices both ways, and spherical linear interpolation.
 */
#ifndef STRAY_QUATERNION_H
#define STRAY_QUATERNION_H

/* M(q) = (q_c^2 - e.e) I + 2 e e^T - 2 q_c [e x] of q = (q_c, e), rows
 * first: frame-A coordinates to frame-B (CCSDS 504.0, stray/aem.h). */
void stray_q_dcm(const double q[4], double m[3][3]);

/* The unit quaternion whose M(q) is m (Shepperd's method). */
void stray_dcm_q(const double m[3][3], double q[4]);

/* Spherical linear interpolation, shortest arc, f in [0, 1]. */
void stray_q_slerp(const double a[4], const double b[4], double f,
		   double q[4]);

#endif /* STRAY_QUATERNION_H */
