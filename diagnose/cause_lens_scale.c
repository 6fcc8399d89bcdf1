/*
 * cause_lens_scale.c - a system curve (baffle + lens, thesis §4.2) whose
 * lens passes more (or less) light from outside its field than the lens
 * table the model was given: the table's out-of-field part (below half
 * its on-axis value) times a factor.  Post-processing (diagnose/lens.c):
 * the light that arrives at the pupil from beyond the lens's field,
 * direct or scattered, traced per incidence bin, scales by the factor;
 * light arriving inside the field does not.  Only with `--lens`.
 */
#include "diagnose/diag_cause.h"

static void apply(const double *p, struct diag_state *s)
{
	s->lens_log10 = p[0];
}

const struct diag_cause diag_cause_lens_scale = {
	.name = "lens_scale",
	.kind = DIAG_POSTPROC,
	.explanation =
	"The lens lets through a different fraction of the light that "
	"arrives from outside its field than its measured table says: the "
	"lens curve is off by one factor beyond the field (a sweep of "
	"another unit, a different filter, a cleaned or dusty front "
	"element). Everything the baffle sends in from outside the field - "
	"the direct beam past the field edge and the scattered light that "
	"arrives at oblique incidence - scales by it; light arriving inside "
	"the field does not. A lens cause, not the baffle's.",
	.n_params = 1,
	.param = { { "log10_factor", "log10(factor)", 0.0, -3.0, 2.0, 11 } },
	.k_bic = 1,
	.apply = apply,
	.needs_lens = 1,
};
