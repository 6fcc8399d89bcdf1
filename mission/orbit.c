/*
 * orbit.c - circular sun-synchronous orbit and anti-nadir attitude.
 */
#include <math.h>

#include "mission/orbit.h"
#include "vec3d.h"

#define TWO_PI 6.28318530717958647692
/* The mean Sun's right-ascension rate: one turn per tropical year. */
#define SUN_RATE_RAD_S (TWO_PI / (365.2421897 * 86400.0))

void orbit_sso(struct orbit *o, double altitude_km, double ltan_h,
	       double sun_ra_rad)
{
	double a = ORBIT_RE_KM + altitude_km, ratio = ORBIT_RE_KM / a;

	o->a_km = a;
	o->n_rad_s = sqrt(ORBIT_MU_KM3_S2 / (a * a * a));
	o->raan_dot_rad_s = SUN_RATE_RAD_S;
	/* Vallado eq. 9-37: RAAN rate = -3/2 n J2 (Re/a)^2 cos i */
	o->incl_rad = acos(-SUN_RATE_RAD_S /
			   (1.5 * o->n_rad_s * ORBIT_J2 * ratio * ratio));
	/* Local time of the node: the node is (ltan - 12 h) east of the Sun. */
	o->raan0_rad = sun_ra_rad + (ltan_h - 12.0) / 24.0 * TWO_PI;
}

void orbit_inclined(struct orbit *o, double altitude_km, double incl_deg,
		    double ltan_h, double sun_ra_rad)
{
	double a = ORBIT_RE_KM + altitude_km, ratio = ORBIT_RE_KM / a;

	o->a_km = a;
	o->n_rad_s = sqrt(ORBIT_MU_KM3_S2 / (a * a * a));
	o->incl_rad = incl_deg * TWO_PI / 360.0;
	o->raan_dot_rad_s = -1.5 * o->n_rad_s * ORBIT_J2 * ratio * ratio *
			    cos(o->incl_rad);
	o->raan0_rad = sun_ra_rad + (ltan_h - 12.0) / 24.0 * TWO_PI;
}

void orbit_state(const struct orbit *o, double t_s, double r[3],
		 double v[3])
{
	double u = o->n_rad_s * t_s, raan = o->raan0_rad + o->raan_dot_rad_s * t_s;
	double cu = cos(u), su = sin(u), cO = cos(raan), sO = sin(raan);
	double ci = cos(o->incl_rad), si = sin(o->incl_rad);
	double speed = o->n_rad_s * o->a_km;

	r[0] = o->a_km * (cO * cu - sO * su * ci);
	r[1] = o->a_km * (sO * cu + cO * su * ci);
	r[2] = o->a_km * (su * si);
	/* d/du of the unit position, times the speed (the slow node drift
	 * changes the direction of v by < 1e-3 deg: neglected) */
	v[0] = speed * (-cO * su - sO * cu * ci);
	v[1] = speed * (-sO * su + cO * cu * ci);
	v[2] = speed * (cu * si);
}

/* Quaternion of a rotation matrix (rows = sensor axes in inertial
 * coordinates), Shepperd's method: divide by the largest of the four. */
static void matrix_to_q(const double m[3][3], double q[4])
{
	double tr = m[0][0] + m[1][1] + m[2][2], s;

	if (tr > 0.0) {
		s = 2.0 * sqrt(1.0 + tr);
		q[0] = 0.25 * s;
		q[1] = (m[2][1] - m[1][2]) / s;
		q[2] = (m[0][2] - m[2][0]) / s;
		q[3] = (m[1][0] - m[0][1]) / s;
	} else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
		s = 2.0 * sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]);
		q[0] = (m[2][1] - m[1][2]) / s;
		q[1] = 0.25 * s;
		q[2] = (m[0][1] + m[1][0]) / s;
		q[3] = (m[0][2] + m[2][0]) / s;
	} else if (m[1][1] > m[2][2]) {
		s = 2.0 * sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]);
		q[0] = (m[0][2] - m[2][0]) / s;
		q[1] = (m[0][1] + m[1][0]) / s;
		q[2] = 0.25 * s;
		q[3] = (m[1][2] + m[2][1]) / s;
	} else {
		s = 2.0 * sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]);
		q[0] = (m[1][0] - m[0][1]) / s;
		q[1] = (m[0][2] + m[2][0]) / s;
		q[2] = (m[1][2] + m[2][1]) / s;
		q[3] = 0.25 * s;
	}
}

void orbit_anti_nadir_q(const double r[3], const double v[3], double q[4])
{
	double m[3][3];
	int k;

	for (k = 0; k < 3; k++) {
		m[2][k] = r[k];		/* +z: zenith */
		m[0][k] = v[k];		/* +x: along track */
	}
	unit(m[2]);
	unit(m[0]);
	/* +y = z cross x completes the right-handed frame */
	m[1][0] = m[2][1] * m[0][2] - m[2][2] * m[0][1];
	m[1][1] = m[2][2] * m[0][0] - m[2][0] * m[0][2];
	m[1][2] = m[2][0] * m[0][1] - m[2][1] * m[0][0];
	matrix_to_q(m, q);
}
