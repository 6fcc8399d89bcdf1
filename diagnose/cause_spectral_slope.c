/*
 * cause_spectral_slope.c - the interior coating's reflectance changes
 * with wavelength (issue 17 item 5): rho(l) = rho0 (l / l0)^s over the
 * band of the source spectrum x the detector's response
 * (diag_spectral.h; l0 its photon-weighted mean wavelength).  A re-weight
 * cause: a path with k interior scatters takes the band moment
 * M_k = <rho(l)^k>, which exceeds <rho(l)>^k for any s != 0, so
 * second- and higher-order paths rise against first-order ones in a way
 * no single grey reflectance reproduces.
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->reflectance = p[0];
	s->spectral_slope = p[1];
}

const struct diag_cause diag_cause_spectral_slope = {
	.name = "spectral_slope",
	.kind = DIAG_REWEIGHT,
	.explanation =
	"The coating's reflectance changes with wavelength (black anodise "
	"and many paints are darker in the blue than in the red or near "
	"infrared), modelled as rho0 (lambda / lambda0)^s over the "
	"detector's band. Each photon keeps its wavelength through all its "
	"bounces, so a twice-scattered path scales as the band mean of "
	"rho^2, larger than the square of the band-mean rho: the second-"
	"order region rises against the first-order one, which a grey "
	"coating of any reflectance cannot do.",
	.n_params = 2,
	.param = { { "reflectance", "1", 0.04, 0.005, 0.30, 4 },
		   { "slope", "1", 0.0, -8.0, 8.0, 5 } },
	.k_bic = 2,
	.apply = apply,
	.nests = "reflectance",
};
