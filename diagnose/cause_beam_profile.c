/*
 * cause_beam_profile.c - the lab beam is not uniform over its directions
 * (issue 17 item 6): a disk of half-angle b whose intensity falls off as
 * exp(-2 r^2 / w^2) with angle r from the axis (w the 1/e^2 radius).
 * The same beam average as cause_beam_divergence.c with a non-uniform
 * weight; it holds beam_divergence as its limit w -> infinity, so BIC
 * names it only when the fall-off is seen (one more parameter): a
 * uniform divergent beam and a Gaussian one of the same second moment
 * differ only in the tails of the smoothed cut-off.
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->beam_half_deg = p[0];
	s->beam_gauss_deg = p[1];
}

const struct diag_cause diag_cause_beam_profile = {
	.name = "beam_profile",
	.kind = DIAG_POSTPROC,
	.explanation =
	"The laboratory beam's intensity falls off with angle from its "
	"axis (a Gaussian of some 1/e^2 radius inside a disk of "
	"directions) rather than filling the disk evenly. Like a uniformly "
	"divergent beam it smooths the steep parts of the curve, with "
	"longer tails and a softer shoulder for the same width.",
	.n_params = 2,
	.param = { { "half_angle_deg", "deg", 0.0, 0.0, 3.0, 3 },
		   { "gauss_radius_deg", "deg", 5.0, 0.2, 5.0, 3 } },
	.k_bic = 2,
	.apply = apply,
	.nests = "beam_divergence",
};
