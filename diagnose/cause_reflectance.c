/*
 * cause_reflectance.c - the interior coating reflects more (or less) than
 * the model's literature value (thesis §4: ~8 % measured against the 4 %
 * the literature gave for black anodise).  A re-weight cause: recorded
 * paths scale as rho^k for k interior scatters (tracer/paths.h).
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->reflectance = p[0];
}

const struct diag_cause diag_cause_reflectance = {
	.name = "reflectance",
	.kind = DIAG_REWEIGHT,
	.explanation =
	"The interior coating reflects a different fraction of light than "
	"the model assumes. Black anodise and paints vary with batch, "
	"thickness, wear and wavelength; literature values are often "
	"lower than what a given part shows. Every k-times scattered path "
	"scales as rho^k, so the scatter-only region rises by the ratio "
	"squared where second-order paths dominate and linearly where "
	"single scatter does, while the directly lit field is unchanged.",
	.n_params = 1,
	.param = { { "reflectance", "1", 0.04, 0.005, 0.30, 7 } },
	.k_bic = 1,
	.apply = apply,
};
