/*
 * diag_spectral.h - the band the diagnosis weights a wavelength-dependent
 * coating over (issue 17 item 5): photon weights of the source spectrum
 * times the detector's response (the photometer's, for a photometer
 * curve; QE for a camera) on a 10 nm grid, and the moments a k-times
 * scattered path takes from a coating rho(l) = rho0 (l / l0)^s:
 *   M_k = sum_i w_i rho(l_i)^k,  not (sum_i w_i rho(l_i))^k,
 * since each path is one photon of one wavelength (thesis eq. 2.1 for
 * the photon weighting).  l0 is the band's photon-weighted mean
 * wavelength, so rho0 is close to the band-mean reflectance.
 */
#ifndef DIAGNOSE_DIAG_SPECTRAL_H
#define DIAGNOSE_DIAG_SPECTRAL_H

#include <stddef.h>

#include "stray/error.h"

#define DIAG_SPECTRAL_BINS 128
#define DIAG_SPECTRAL_DEFAULT_SOURCE "builtin:sun_am0_astm_e490"
#define DIAG_SPECTRAL_DEFAULT_RESPONSE "builtin:qe_mt9p031_approx"

struct diag_band {
	size_t n;
	double lambda_nm[DIAG_SPECTRAL_BINS], w[DIAG_SPECTRAL_BINS];
	double lambda0_nm;	/* photon-weighted mean */
};

/* The band of a source spectrum and a response (spectrum_io.h sources:
 * a CSV path or builtin:NAME); errors name the file. */
int diag_band_load(const char *source, const char *response,
		   struct diag_band *b, struct stray_error *err);

/* The band the evaluator uses (set before the fit; default: the Sun
 * AM0 spectrum times the built-in QE, loaded on first use). */
int diag_band_set(const char *source, const char *response,
		  struct stray_error *err);
const struct diag_band *diag_band_current(void);

/* pw[k] = sum_i w_i (rho (l_i / l0)^slope)^k for k = 0..kmax. */
void diag_band_moments(const struct diag_band *b, double rho, double slope,
		       double *pw, int kmax);

#endif /* DIAGNOSE_DIAG_SPECTRAL_H */
