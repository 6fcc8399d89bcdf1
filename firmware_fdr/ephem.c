/*
 * ephem.c - low-precision Sun and Moon for the on-board flags.
 *
 * Mean arguments a0 + n t are kept as 64-bit fractions of a revolution:
 * unsigned arithmetic wraps modulo 2^64, i.e. modulo one revolution, so
 * a + n t is reduced exactly (to 2^-64 rev) whatever t is, and only the
 * reduced angle meets single precision (2^-24 rev = 0.00002 deg).  A float
 * t in centuries would lose 0.02 deg on the Moon's mean longitude by 2040.
 *
 * Periodic terms are in float; their total error budget is far below the
 * model's own (Sun ~0.003 deg, Moon ~0.03 deg, measured against ERFA in
 * tests/firmware_fdr/test_ephem.c).
 */
#include <math.h>

#include "fdrfw/ephem.h"

#define TWO_PI 6.28318530717958648f
#define DEG 0.0174532925199432958f
#define ARCSEC 4.84813681109535994e-6f

/* 2^64 as a double, to build the fixed-point constants at compile time. */
#define Q64 18446744073709551616.0
/* A phase given in degrees (0 <= deg < 360) as a fraction of 2^64. */
#define PHASE_DEG(deg) ((uint64_t)((deg) / 360.0 * Q64))
/* A rate in degrees per Julian century as 2^-64 rev per second. */
#define RATE_DEG_CY(r) ((uint64_t)((r) / 360.0 / 3155760000.0 * Q64))
/* A rate in revolutions per Julian century as 2^-64 rev per second. */
#define RATE_REV_CY(r) ((uint64_t)((r) / 3155760000.0 * Q64))

#define SECONDS_PER_CENTURY 3155760000.0f
/* General precession in longitude, 5029.0966"/cy (IAU 2006, Capitaine
 * et al. 2003): the equinox of date runs ahead of J2000's. */
#define PRECESSION_DEG_CY 1.3969713f
/* Mean obliquity of J2000, 84381.406" (IAU 2006). */
#define OBLIQUITY_J2000 (84381.406f * ARCSEC)

/* The ecliptic of date is tilted to J2000's by pi_A = 47.0029" T about a
 * node at Pi_A = 174.876384 deg (Lieske et al. 1977, A&A 58, 1): a point
 * of latitude 0 on it has J2000 latitude pi_A T sin(lon - Pi_A). */
#define ECLIPTIC_TILT_CY (47.0029f * ARCSEC)
#define ECLIPTIC_NODE (174.876384f * DEG)

/* a0 + rate * t, reduced to [0, 2 pi). */
static float mean_arg(uint64_t a0, uint64_t rate, int32_t t_s)
{
	uint64_t phase = a0 + (uint64_t)(int64_t)t_s * rate;

	return (float)(uint32_t)(phase >> 40) * (TWO_PI / 16777216.0f);
}

/* Ecliptic (longitude, latitude) of J2000 -> equatorial unit vector. */
static void ecliptic_to_equatorial(float lon, float lat, float u[3])
{
	float cl = cosf(lat), x = cl * cosf(lon), y = cl * sinf(lon);
	float z = sinf(lat), ce = cosf(OBLIQUITY_J2000);
	float se = sinf(OBLIQUITY_J2000);

	u[0] = x;
	u[1] = ce * y - se * z;
	u[2] = se * y + ce * z;
}

void fdrfw_sun_dir(int32_t t_tt_s, float u[3])
{
	/* Meeus ch. 25: geometric mean longitude L0 and mean anomaly M; L0's
	 * rate is taken relative to the fixed J2000 equinox. */
	float t_cy = (float)t_tt_s / SECONDS_PER_CENTURY;
	float l0 = mean_arg(PHASE_DEG(280.46646),
			    RATE_DEG_CY(36000.76983 - 1.3969713), t_tt_s);
	float m = mean_arg(PHASE_DEG(357.52911), RATE_DEG_CY(35999.05029),
			   t_tt_s);
	/* Equation of the centre C (Meeus eq. 25.4 and the line after). */
	float c = ((1.914602f - 0.004817f * t_cy) * sinf(m) +
		   (0.019993f - 0.000101f * t_cy) * sinf(2.0f * m) +
		   0.000289f * sinf(3.0f * m)) * DEG;

	/* Earth sits 4671 km from the Earth-Moon barycentre, towards minus
	 * the Moon: seen from the Sun 6.44" along the elongation D. */
	float d = mean_arg(PHASE_DEG(0.827361 * 360.0),
			   RATE_REV_CY(1236.853086), t_tt_s);
	float lon = l0 + c + 6.44f * ARCSEC * sinf(d);

	ecliptic_to_equatorial(lon, ECLIPTIC_TILT_CY * t_cy *
			       sinf(lon - ECLIPTIC_NODE), u);
}

/* Periodic terms of the Moon's longitude [arcsec] (MiniMoon). */
static float moon_dlon(float l, float ls, float d, float f)
{
	return 22640.0f * sinf(l) - 4586.0f * sinf(l - 2.0f * d) +
	       2370.0f * sinf(2.0f * d) + 769.0f * sinf(2.0f * l) -
	       668.0f * sinf(ls) - 412.0f * sinf(2.0f * f) -
	       212.0f * sinf(2.0f * l - 2.0f * d) -
	       206.0f * sinf(l + ls - 2.0f * d) + 192.0f * sinf(l + 2.0f * d) -
	       165.0f * sinf(ls - 2.0f * d) - 125.0f * sinf(d) -
	       110.0f * sinf(l + ls) + 148.0f * sinf(l - ls) -
	       55.0f * sinf(2.0f * f - 2.0f * d);
}

/* Latitude [rad] (MiniMoon: S and the N terms). */
static float moon_lat(float l, float ls, float d, float f, float dlon)
{
	float s = f + (dlon + 412.0f * sinf(2.0f * f) + 541.0f * sinf(ls)) *
		      ARCSEC;
	float h = f - 2.0f * d;
	float n = -526.0f * sinf(h) + 44.0f * sinf(l + h) -
		  31.0f * sinf(-l + h) - 23.0f * sinf(ls + h) +
		  11.0f * sinf(-ls + h) - 25.0f * sinf(-2.0f * l + f) +
		  21.0f * sinf(-l + f);

	return (18520.0f * sinf(s) + n) * ARCSEC;
}

/* Distance [km]: Meeus table 47.A, terms above 100 km. */
static float moon_dist_km(float l, float ls, float d)
{
	return 385000.56f - 20905.355f * cosf(l) -
	       3699.111f * cosf(2.0f * d - l) - 2955.968f * cosf(2.0f * d) -
	       569.925f * cosf(2.0f * l) +
	       246.158f * cosf(2.0f * d - 2.0f * l) -
	       204.586f * cosf(2.0f * d - ls) - 170.733f * cosf(2.0f * d + l) -
	       152.138f * cosf(2.0f * d - ls - l) - 129.620f * cosf(l - ls) +
	       108.743f * cosf(d) + 104.755f * cosf(l + ls);
}

void fdrfw_moon_pos_km(int32_t t_tt_s, float r_km[3])
{
	/* MiniMoon mean arguments [rev/cy]: mean longitude L0, anomalies l
	 * (Moon) and ls (Sun), elongation D, argument of latitude F. */
	float t_cy = (float)t_tt_s / SECONDS_PER_CENTURY;
	float l0 = mean_arg(PHASE_DEG(0.606433 * 360.0),
			    RATE_REV_CY(1336.855225), t_tt_s);
	float l = mean_arg(PHASE_DEG(0.374897 * 360.0),
			   RATE_REV_CY(1325.552410), t_tt_s);
	float ls = mean_arg(PHASE_DEG(0.993133 * 360.0),
			    RATE_REV_CY(99.997361), t_tt_s);
	float d = mean_arg(PHASE_DEG(0.827361 * 360.0),
			   RATE_REV_CY(1236.853086), t_tt_s);
	float f = mean_arg(PHASE_DEG(0.259086 * 360.0),
			   RATE_REV_CY(1342.227825), t_tt_s);
	float dlon = moon_dlon(l, ls, d, f);
	float lon = l0 + dlon * ARCSEC - PRECESSION_DEG_CY * DEG * t_cy;
	float u[3], dist = moon_dist_km(l, ls, d);

	ecliptic_to_equatorial(lon, moon_lat(l, ls, d, f, dlon) +
			       ECLIPTIC_TILT_CY * t_cy *
			       sinf(lon - ECLIPTIC_NODE), u);
	r_km[0] = dist * u[0];
	r_km[1] = dist * u[1];
	r_km[2] = dist * u[2];
}
