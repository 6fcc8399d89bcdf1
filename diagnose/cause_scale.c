/*
 * cause_scale.c - the whole curve off by a factor: the absolute level of
 * a flight curve (`stray flightcheck`, thesis §4.3) against a model whose
 * normalisation (k_px, the lens's transmission, the Sun's flux in the
 * passband) is wrong.  Post-processing: alpha_meas = 10^s alpha_model.
 * Only for curves without a theta = 0 point (a lab curve normalised by
 * its own on-axis point has no free scale).
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->scale_log10 = p[0];
}

const struct diag_cause diag_cause_scale = {
	.name = "scale",
	.kind = DIAG_POSTPROC,
	.explanation =
	"The measured curve is the model's times one factor at every angle: "
	"the absolute level is off while the shape is right. In orbit, where "
	"the Sun cannot be dimmed and the background is calibrated on the "
	"catalogue stars, this is the per-pixel normalisation k_px (how the "
	"stray power spreads over the detector), a lens or filter "
	"transmission the model lacks, or the Sun's flux in the passband.",
	.n_params = 1,
	.param = { { "log10_scale", "log10(factor)", 0.0, -6.0, 3.0, 10 } },
	.k_bic = 1,
	.apply = apply,
	.needs_unnormalised = 1,
};
