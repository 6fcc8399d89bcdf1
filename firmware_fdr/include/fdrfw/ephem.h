/*
 * ephem.h - on-board low-precision Sun and Moon directions.
 *
 * Time is whole seconds since J2000.0 TT (2000-01-01 12:00:00 TT) as a
 * signed 32-bit count (valid 1932-2068).  Mean arguments are advanced in
 * 64-bit fixed point (fractions of a revolution), so a float on the target
 * holds only the reduced angle and loses nothing to the size of t.
 *
 * Frame: mean equator and equinox of J2000 (ICRF to 0.02"), the frame a
 * star catalogue gives the attitude in.  Directions are geometric.
 */
#ifndef FDRFW_EPHEM_H
#define FDRFW_EPHEM_H

#include <stdint.h>

/* Unit vector Earth -> Sun (Meeus, Astronomical Algorithms, ch. 25). */
void fdrfw_sun_dir(int32_t t_tt_s, float u[3]);

/*
 * Geocentric Moon position [km] (Montenbruck & Pfleger, Astronomy on the
 * Personal Computer, 4th ed., §3.2 MiniMoon, with Meeus ch. 47's main
 * distance terms).
 */
void fdrfw_moon_pos_km(int32_t t_tt_s, float r_km[3]);

#endif /* FDRFW_EPHEM_H */
