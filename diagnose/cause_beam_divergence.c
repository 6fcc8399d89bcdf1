/*
 * cause_beam_divergence.c - the lab beam is not collimated (issue 17
 * item 6): its directions fill a disk of half-angle b about the nominal
 * one, so each measured point is the model averaged over that disk (and
 * normalised by the same average about theta = 0).  Post-processing of
 * the traced curve on its fine angle grid (evaluate.c, beam_factor).
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->beam_half_deg = p[0];
	s->beam_gauss_deg = 0.0;
}

const struct diag_cause diag_cause_beam_divergence = {
	.name = "beam_divergence",
	.kind = DIAG_POSTPROC,
	.explanation =
	"The laboratory beam diverges: its light arrives from a disk of "
	"directions of some half-angle (a source of finite size at the "
	"collimator's focus), so every point is the model averaged over "
	"that disk. Steep parts of the curve - the edge of the direct "
	"beam, the fall into the scatter region - are smoothed: the "
	"cut-off is less sharp, the last lit angles read low and the first "
	"shadowed ones high, while flat parts are unchanged.",
	.n_params = 1,
	.param = { { "half_angle_deg", "deg", 0.0, 0.0, 3.0, 4 } },
	.k_bic = 1,
	.apply = apply,
};
