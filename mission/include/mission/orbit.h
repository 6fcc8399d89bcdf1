/*
 * orbit.h - a circular sun-synchronous orbit and an anti-nadir attitude,
 * for evaluating the flight module along a day in orbit (make demo).
 *
 * Two-body circular motion with the J2 nodal regression that makes the
 * orbit sun-synchronous (Vallado, Fundamentals of Astrodynamics and
 * Applications, 4th ed., §9.6, eq. 9-37); no drag, no other harmonics:
 * good to the tens of km that matter for the Earth's angular radius.
 */
#ifndef STRAY_MISSION_ORBIT_H
#define STRAY_MISSION_ORBIT_H

#define ORBIT_MU_KM3_S2 398600.4418	/* Earth's GM (WGS 84) */
#define ORBIT_RE_KM 6378.137		/* equatorial radius (WGS 84) */
#define ORBIT_J2 1.08262668e-3

struct orbit {
	double a_km;		/* semi-major axis */
	double incl_rad;	/* sun-synchronous inclination */
	double raan0_rad;	/* right ascension of the ascending node at t0 */
	double n_rad_s;		/* mean motion */
	double raan_dot_rad_s;	/* J2 regression = the Sun's mean motion */
};

/*
 * A sun-synchronous orbit at altitude_km whose ascending node crosses at
 * local time ltan_h, given the Sun's right ascension at t0.
 */
void orbit_sso(struct orbit *o, double altitude_km, double ltan_h,
	       double sun_ra_rad);

/*
 * A circular orbit at altitude_km and inclination incl_deg whose node is
 * at local time ltan_h at t0; the node regresses by J2 alone (Vallado
 * eq. 9-37), so it keeps its local time only when sun-synchronous.
 */
void orbit_inclined(struct orbit *o, double altitude_km, double incl_deg,
		    double ltan_h, double sun_ra_rad);

/* Position [km] and velocity [km/s] t_s after t0 (argument of latitude
 * 0 at t0), geocentric inertial (J2000). */
void orbit_state(const struct orbit *o, double t_s, double r[3],
		 double v[3]);

/*
 * The attitude quaternion (w, x, y, z), inertial -> sensor, of a sensor
 * whose boresight (+z) points away from the Earth's centre and whose +x
 * lies along the velocity.
 */
void orbit_anti_nadir_q(const double r[3], const double v[3], double q[4]);

#endif /* STRAY_MISSION_ORBIT_H */
