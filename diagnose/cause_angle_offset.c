/*
 * cause_angle_offset.c - the rotation stage's zero is off: every measured
 * point was taken at theta + offset.  Measurement post-processing: the
 * model is read at the shifted angle by log-linear interpolation on a
 * finer traced grid around each measured angle.
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->angle_offset_deg = p[0];
}

const struct diag_cause diag_cause_angle_offset = {
	.name = "angle_offset",
	.kind = DIAG_POSTPROC,
	.explanation =
	"The rotation stage's zero is not the optical axis: every point "
	"was measured at the logged angle plus a constant offset. Where "
	"the curve is steep - the edge of the direct beam, the fall into "
	"the scatter region - a fraction of a degree changes alpha by tens "
	"of percent, with the sign of the local slope; where it is flat "
	"nothing changes.",
	.n_params = 1,
	.param = { { "offset_deg", "deg", 0.0, -DIAG_OFFSET_MAX_DEG,
		     DIAG_OFFSET_MAX_DEG, 5 } },
	.k_bic = 1,
	.apply = apply,
};
