/*
 * quaternion.c - CCSDS 504.0 quaternions and their direction-cosine
 * matrices (stray/quaternion.h), for the AEM reader (aem.c), its other
 * attitude types (aem_types.c) and SLERP between records.
 */
#include <math.h>

#include "stray/quaternion.h"

void stray_q_dcm(const double q[4], double m[3][3])
{
	double c = q[0], e[3] = { q[1], q[2], q[3] };
	double s = c * c - (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
	/* [e x] */
	double x[3][3] = { { 0, -e[2], e[1] }, { e[2], 0, -e[0] },
			   { -e[1], e[0], 0 } };
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			m[i][j] = (i == j ? s : 0.0) + 2.0 * e[i] * e[j] -
				  2.0 * c * x[i][j];
}

void stray_dcm_q(const double m[3][3], double q[4])
{
	double tr = m[0][0] + m[1][1] + m[2][2], s;

	/* Shepperd for M = R(q)^T: the signs of the skew parts flip */
	if (tr > 0.0) {
		s = 2.0 * sqrt(1.0 + tr);
		q[0] = 0.25 * s;
		q[1] = (m[1][2] - m[2][1]) / s;
		q[2] = (m[2][0] - m[0][2]) / s;
		q[3] = (m[0][1] - m[1][0]) / s;
	} else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
		s = 2.0 * sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
		q[0] = (m[1][2] - m[2][1]) / s;
		q[1] = 0.25 * s;
		q[2] = (m[0][1] + m[1][0]) / s;
		q[3] = (m[0][2] + m[2][0]) / s;
	} else if (m[1][1] > m[2][2]) {
		s = 2.0 * sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
		q[0] = (m[2][0] - m[0][2]) / s;
		q[1] = (m[0][1] + m[1][0]) / s;
		q[2] = 0.25 * s;
		q[3] = (m[1][2] + m[2][1]) / s;
	} else {
		s = 2.0 * sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
		q[0] = (m[0][1] - m[1][0]) / s;
		q[1] = (m[0][2] + m[2][0]) / s;
		q[2] = (m[1][2] + m[2][1]) / s;
		q[3] = 0.25 * s;
	}
}

void stray_q_slerp(const double a[4], const double b[4], double f,
		   double q[4])
{
	double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
	double sb = 1.0, wa, wb, n;
	int k;

	if (d < 0.0) {
		d = -d;
		sb = -1.0;
	}
	if (d > 0.9999995) {	/* nearly equal: linear, then renormalised */
		wa = 1.0 - f;
		wb = f;
	} else {
		double th = acos(d), s = sin(th);

		wa = sin((1.0 - f) * th) / s;
		wb = sin(f * th) / s;
	}
	for (k = 0; k < 4; k++)
		q[k] = wa * a[k] + sb * wb * b[k];
	n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
	for (k = 0; k < 4; k++)
		q[k] /= n;
}
