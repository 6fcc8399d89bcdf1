/*
 * cause_floor.c - a constant additive floor (room light, atmospheric
 * scatter of the source beam, detector offset).  Post-processing:
 * alpha_meas = alpha_model + F.
 */
#include <math.h>

#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->floor = pow(10.0, p[0]);
}

const struct diag_cause diag_cause_floor = {
	.name = "floor",
	.kind = DIAG_POSTPROC,
	.explanation =
	"A constant background adds to every measurement: ambient light in "
	"the laboratory, scatter of the source beam by air and dust seen "
	"by the detector, or an uncorrected detector offset. It is "
	"invisible where the baffle passes much light and dominates where "
	"the baffle rejects best, flattening the deepest part of the "
	"curve.",
	.n_params = 1,
	.param = { { "log10_floor", "log10(alpha)", -12.0, -9.0, -3.0, 7 } },
	.k_bic = 1,
	.apply = apply,
};
