/*
 * photometry.h - passband photometry (thesis §2.1, eq. 2.1-2.2).
 * Freestanding: spectra are views of caller-owned arrays.
 */
#ifndef STRAY_PHOTOMETRY_H
#define STRAY_PHOTOMETRY_H

#include <stddef.h>

#include "stray/config.h"
#include "stray/error.h"

/* Physical constants, CODATA 2018 exact values (SI). */
#define STRAY_PLANCK_J_S 6.62607015e-34
#define STRAY_LIGHT_SPEED_M_S 299792458.0
#define STRAY_BOLTZMANN_J_K 1.380649e-23

/*
 * A sampled curve of wavelength: spectral irradiance [W m^-2 nm^-1] or a
 * response (quantum efficiency, 0..1).  Linear between samples, zero
 * outside [wavelength_nm[0], wavelength_nm[n-1]].
 */
struct stray_spectrum {
	size_t n;
	const double *wavelength_nm;	/* strictly increasing */
	const double *value;		/* >= 0 */
};

/* Wavelengths finite, > 0 and strictly increasing; values finite, >= 0. */
int stray_spectrum_check(const struct stray_spectrum *s,
			 struct stray_error *err);

/* The linear interpolant of s at lambda_nm, zero outside its support. */
double stray_spectrum_at(const struct stray_spectrum *s, double lambda_nm);

/*
 * eq. 2.1: F = integral f(l) S(l) l/(h c) dl [photons s^-1 m^-2].  The
 * integrand is a product of two piecewise-linear curves times l, a cubic on
 * each interval of the union of both grids, so Simpson's rule on that
 * union is exact for the interpolated curves.
 */
int stray_photon_flux(const struct stray_spectrum *irradiance,
		      const struct stray_spectrum *response,
		      double *flux_ph_s_m2, struct stray_error *err);

/* eq. 2.2 inverted: the zero-magnitude flux F_0 = F_ref 10^(0.4 m_ref). */
double stray_zero_mag_flux(double f_ref_ph_s_m2, double m_ref);

/* eq. 2.2: F(m) = F_0 10^(-0.4 m). */
double stray_mag_to_flux(double f0_ph_s_m2, double mag);

/* eq. 2.2: m = -2.5 log10(F / F_0). */
double stray_flux_to_mag(double f0_ph_s_m2, double flux_ph_s_m2);

/*
 * Lunar magnitude at phase angle phase_deg (0 = full), from the full-Moon
 * magnitude by Allen's phase law m(p) = m_full + 0.026|p| + 4e-9 p^4
 * (Allen's Astrophysical Quantities, 4th ed., §12.4).  In the core's real
 * type (config.h), since the flight module evaluates it every frame.
 */
stray_real stray_moon_mag_at_phase(stray_real m_full, stray_real phase_deg);

/*
 * Photon flux on an aperture facing the centre of a fully sunlit Lambertian
 * Earth from altitude_m: albedo * F_sun * sin^2(rho), rho the angular
 * radius of the Earth (irradiance of a uniform-radiance disc, pi L sin^2
 * rho, with L = albedo E_sun / pi).  An upper bound on the limb source.
 */
int stray_earth_flux(double f_sun_ph_s_m2, double albedo, double altitude_m,
		     double *flux_ph_s_m2, struct stray_error *err);

/* Mean Earth radius [m] (IUGG). */
#define STRAY_EARTH_RADIUS_M 6371008.8

#endif /* STRAY_PHOTOMETRY_H */
