/*
 * aem_types.c - every attitude type of 504.0 converted once, on reading,
 * to the direction-cosine matrix the AEM reader turns into its
 * quaternion: missions deliver Euler angles and spin data as often as
 * quaternions.  Rates and derivatives are checked as numbers and not
 * used (the flight module interpolates attitude by SLERP).
 */
#include <math.h>
#include <string.h>

#include "aem_types.h"
#include "stray/ccsds.h"
#include "stray/quaternion.h"

#define D2R 1.745329251994329576923691e-2

static const struct { const char *name; int type; } names[] = {
	{ "QUATERNION", AEM_QUATERNION },
	{ "QUATERNION/DERIVATIVE", AEM_QUATERNION_DERIV },
	{ "QUATERNION/RATE", AEM_QUATERNION_RATE },	/* version 1 */
	{ "QUATERNION/ANGVEL", AEM_QUATERNION_RATE },	/* version 2 */
	{ "EULER_ANGLE", AEM_EULER },
	{ "EULER_ANGLE/RATE", AEM_EULER_RATE },		/* version 1 */
	{ "EULER_ANGLE/DERIVATIVE", AEM_EULER_RATE },	/* version 2 */
	{ "EULER_ANGLE/ANGVEL", AEM_EULER_RATE },	/* version 2 */
	{ "SPIN", AEM_SPIN },
	{ "SPIN/NUTATION", AEM_SPIN_NUTATION },
	{ "SPIN/NUTATION_MOM", AEM_SPIN_NUTATION },	/* version 2 */
};

int aem_type(const char *value)
{
	size_t i;

	for (i = 0; i < sizeof(names) / sizeof(names[0]); i++)
		if (stray_kvn_eq(value, names[i].name))
			return names[i].type;
	return -1;
}

int aem_type_fields(int type)
{
	static const int n[] = { 4, 8, 7, 3, 6, 4, 7 };

	return n[type];
}

int aem_type_is_quaternion(int type)
{
	return type <= AEM_QUATERNION_RATE;
}

int aem_type_is_euler(int type)
{
	return type == AEM_EULER || type == AEM_EULER_RATE;
}

int aem_euler_seq(const char *v, int axis[3])
{
	int i;

	if (strlen(v) != 3)
		return -1;
	for (i = 0; i < 3; i++) {
		char c = v[i];

		if (c >= '1' && c <= '3')
			axis[i] = c - '1';
		else if (c == 'X' || c == 'x')
			axis[i] = 0;
		else if (c == 'Y' || c == 'y')
			axis[i] = 1;
		else if (c == 'Z' || c == 'z')
			axis[i] = 2;
		else
			return -1;
	}
	/* 1-1-2 is not a sequence: a rotation twice about one axis */
	return axis[0] != axis[1] && axis[1] != axis[2] ? 0 : -1;
}

void aem_axis_dcm(int axis, double a, double m[3][3])
{
	int i = (axis + 1) % 3, j = (axis + 2) % 3;

	memset(m, 0, 9 * sizeof(double));
	m[axis][axis] = 1.0;
	m[i][i] = m[j][j] = cos(a);
	m[i][j] = sin(a);
	m[j][i] = -sin(a);
}

/* o = a b */
static void mul(const double a[3][3], const double b[3][3], double o[3][3])
{
	double t[3][3];
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			for (t[i][j] = 0.0, k = 0; k < 3; k++)
				t[i][j] += a[i][k] * b[k][j];
	memcpy(o, t, sizeof(t));
}

static void euler(const int axis[3], const double ang[3], double m[3][3])
{
	double r[3][3];
	int k;

	aem_axis_dcm(axis[0], ang[0], m);
	for (k = 1; k < 3; k++) {
		aem_axis_dcm(axis[k], ang[k], r);
		mul(r, m, m);
	}
}

void aem_type_dcm(int type, const double *x, int q_first,
		  const int axis[3], double m[3][3], double *norm)
{
	double q[4], a[3];
	int k;

	*norm = 1.0;
	if (aem_type_is_quaternion(type)) {
		q[0] = q_first ? x[0] : x[3];
		for (k = 0; k < 3; k++)
			q[k + 1] = q_first ? x[k + 1] : x[k];
		*norm = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] +
			     q[3] * q[3]);
		for (k = 0; k < 4; k++)
			q[k] /= *norm;
		stray_q_dcm(q, m);
		return;
	}
	if (aem_type_is_euler(type)) {
		for (k = 0; k < 3; k++)
			a[k] = x[k] * D2R;
		euler(axis, a, m);
		return;
	}
	/* spin: body z on the spin axis (alpha, delta), phi about it */
	a[0] = (90.0 + x[0]) * D2R;
	a[1] = (90.0 - x[1]) * D2R;
	a[2] = x[2] * D2R;
	euler((const int[3]){ 2, 0, 2 }, a, m);
}
