/*
 * earth.c - quadrature nodes over the visible Earth (see earth.h).
 *
 * Each node is a direction from the spacecraft into the Earth's cap; the
 * surface point it meets (ray and sphere, closed form) gives the cosine
 * of the Sun's incidence there, from which the caller forms the Lambertian
 * radiance L = albedo E_sun cos(i) / pi.
 */
#include <math.h>

#include "fdrfw/earth.h"
#include "fdrfw/vec.h"

#define TWO_PI 6.28318530717958648f
#define QUARTER_PI 0.785398163397448310f
#define RAD_TO_DEG 57.29577951308232f

/* Gauss-Legendre nodes and weights on [-1, 1], n = 6 (Abramowitz &
 * Stegun, table 25.4). */
static const float gl_x[FDRFW_EARTH_NU] = {
	-0.932469514203152f, -0.661209386466265f, -0.238619186083197f,
	0.238619186083197f, 0.661209386466265f, 0.932469514203152f
};
static const float gl_w[FDRFW_EARTH_NU] = {
	0.171324492379170f, 0.360761573048139f, 0.467913934572691f,
	0.467913934572691f, 0.360761573048139f, 0.171324492379170f
};

/* Two unit vectors completing n to a right-handed orthonormal frame. */
static void frame_about(const float n[3], float e1[3], float e2[3])
{
	float a[3] = { 0.0f, 0.0f, 0.0f };
	float c[3];

	/* The axis least aligned with n keeps the cross product well sized. */
	if (fabsf(n[0]) <= fabsf(n[1]) && fabsf(n[0]) <= fabsf(n[2]))
		a[0] = 1.0f;
	else if (fabsf(n[1]) <= fabsf(n[2]))
		a[1] = 1.0f;
	else
		a[2] = 1.0f;
	fdrfw_cross(n, a, c);
	(void)fdrfw_unit(c, e1);
	fdrfw_cross(n, e1, e2);
}

int fdrfw_earth_cap(const float pos_km[3], const float sun[3],
		    struct fdrfw_earth_cap *cap)
{
	float r = fdrfw_norm(pos_km), sin_rho;
	unsigned i;

	if (!(isfinite(r) && r > FDRFW_EARTH_RADIUS_KM))
		return 0;
	for (i = 0; i < 3u; i++) {
		cap->pos_km[i] = pos_km[i];
		cap->sun[i] = sun[i];
		cap->nadir[i] = -pos_km[i] / r;
	}
	frame_about(cap->nadir, cap->e1, cap->e2);
	cap->r_km = r;
	sin_rho = FDRFW_EARTH_RADIUS_KM / r;
	cap->cos_rho = sqrtf(1.0f - sin_rho * sin_rho);
	cap->one_minus_cos_rho = sin_rho * sin_rho / (1.0f + cap->cos_rho);
	cap->rho_deg = asinf(sin_rho) * RAD_TO_DEG;
	return 1;
}

void fdrfw_earth_node(const struct fdrfw_earth_cap *cap, unsigned idx,
		      struct fdrfw_earth_node *k)
{
	unsigned iu = (idx / FDRFW_EARTH_NPHI) % FDRFW_EARTH_NU;
	unsigned ip = idx % FDRFW_EARTH_NPHI, i;
	/* sin(gamma) = sin(rho) sin(t), t in [0, pi/2]: cos(t) is then the
	 * cosine of the emission angle at the surface point, so the limb's
	 * square-root edge becomes smooth in t. */
	float t = QUARTER_PI * (1.0f + gl_x[iu]);
	float sin_t = sinf(t), cos_t = cosf(t);
	float sin_rho = FDRFW_EARTH_RADIUS_KM / cap->r_km;
	float sin_g = sin_rho * sin_t;
	float cos_g = sqrtf(1.0f - sin_g * sin_g);
	float phi = TWO_PI * ((float)ip + 0.5f) / (float)FDRFW_EARTH_NPHI;
	float dist, x[3];

	for (i = 0; i < 3u; i++)
		k->dir[i] = cos_g * cap->nadir[i] + sin_g *
			    (cosf(phi) * cap->e1[i] + sinf(phi) * cap->e2[i]);
	/* Near intersection with the sphere: r cos(g) - R cos(t). */
	dist = cap->r_km * cos_g - FDRFW_EARTH_RADIUS_KM * cos_t;
	for (i = 0; i < 3u; i++)
		x[i] = (cap->pos_km[i] + dist * k->dir[i]) /
		       FDRFW_EARTH_RADIUS_KM;
	k->cos_gamma = cos_g;
	k->cos_sun = fmaxf(0.0f, fdrfw_dot(x, cap->sun));
	/* dOmega = sin(g) dg dphi, dg = sin(rho) cos(t) dt / cos(g). */
	k->omega_sr = sin_g * sin_rho * cos_t / cos_g * QUARTER_PI *
		      gl_w[iu] * TWO_PI / (float)FDRFW_EARTH_NPHI;
}
