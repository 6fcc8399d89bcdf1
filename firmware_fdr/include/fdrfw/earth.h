/*
 * earth.h - the sunlit Earth as an extended stray-light source.
 *
 * Seen from the spacecraft the Earth fills a cap of angular radius rho,
 * sin rho = R / r.  The cap is integrated with a fixed product rule:
 * Gauss-Legendre in t, where sin(gamma) = sin(rho) sin(t) (gamma from
 * nadir, t in [0, pi/2]; cos t is the cosine of emission at the ground,
 * so the limb is smooth in t), and the midpoint rule in azimuth.  Tested
 * against the closed forms of a uniform disc, its solid angle
 * 2 pi (1 - cos rho) and its irradiance on a plane facing nadir
 * pi L sin^2 rho, and Lambert's phase law of a distant sphere.
 */
#ifndef FDRFW_EARTH_H
#define FDRFW_EARTH_H

#define FDRFW_EARTH_NU 6u	/* Gauss-Legendre nodes in t */
#define FDRFW_EARTH_NPHI 12u	/* azimuth nodes */
#define FDRFW_EARTH_NODES (FDRFW_EARTH_NU * FDRFW_EARTH_NPHI)
#define FDRFW_EARTH_RADIUS_KM 6371.0088f	/* mean radius (IUGG) */

struct fdrfw_earth_node {
	float dir[3];		/* unit vector spacecraft -> surface point */
	float omega_sr;		/* solid-angle weight */
	float cos_gamma;	/* cosine of the angle from nadir */
	float cos_sun;		/* cosine of the Sun's incidence, 0 at night */
};

/* The cap seen from one position; nodes are made one at a time from it,
 * so the stack never holds all of them. */
struct fdrfw_earth_cap {
	float pos_km[3];
	float sun[3];
	float nadir[3], e1[3], e2[3];
	float r_km;
	float cos_rho;
	float one_minus_cos_rho;	/* without cancellation when far */
	float rho_deg;		/* angular radius of the Earth */
};

/*
 * The cap for a spacecraft at pos_km (geocentric) and the Sun direction
 * sun (unit).  Returns 0 if the spacecraft is not above the surface.
 */
int fdrfw_earth_cap(const float pos_km[3], const float sun[3],
		    struct fdrfw_earth_cap *cap);

/* Node idx (0 .. FDRFW_EARTH_NODES-1) of the quadrature over cap. */
void fdrfw_earth_node(const struct fdrfw_earth_cap *cap, unsigned idx,
		      struct fdrfw_earth_node *k);

#endif /* FDRFW_EARTH_H */
