/*
 * cause_bevel_face.c - the vanes were mounted or machined with the bevel
 * on the other (upper, sky-side) face.  A discrete re-trace: one trace of
 * the flipped baffle; counted as one parameter by BIC.
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	(void)p;
	s->geo[DIAG_GEO_BEVEL_UPPER] = 1.0;
}

const struct diag_cause diag_cause_bevel_face = {
	.name = "bevel_face",
	.kind = DIAG_RETRACE,
	.explanation =
	"The knife-edge bevels are on the other face of the vanes than "
	"designed (an assembly or drawing error). With the bevel facing "
	"the sky the bevel surfaces are lit at moderate angles and seen by "
	"the detector, raising the transition region, while above about "
	"45 deg the far-side bevels no longer face the detector and the "
	"high-angle rise of the design disappears.",
	.n_params = 0,
	.k_bic = 1,
	.apply = apply,
	.geo_axis = DIAG_GEO_BEVEL_UPPER,
	.needs_baffle = 1,
};
