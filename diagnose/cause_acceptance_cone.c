/*
 * cause_acceptance_cone.c - the photometer accepts light only within a
 * cone narrower than the baffle's field (thesis §4: narrower than the
 * field below 25 deg).  It changes which detector-side paths count, so
 * it is re-traced on a grid of half-angles and interpolated between.
 */
#include "diagnose/diag_cause.h"

static const double nodes[] = { 15.0, 20.0, 25.0, 30.0, 40.0, 60.0,
				90.0 };

static void apply(const double *p, struct diag_state *s)
{
	s->geo[DIAG_GEO_ACCEPT] = p[0];
}

const struct diag_cause diag_cause_acceptance_cone = {
	.name = "acceptance_cone",
	.kind = DIAG_RETRACE,
	.explanation =
	"The measuring detector (a photometer) accepts light only within a "
	"cone narrower than the angles at which stray light reaches the "
	"lens pupil. Light arriving obliquely - the direct beam beyond the "
	"cone's half-angle and scatter from the vanes and walls seen at "
	"grazing angles - is not counted, so the measured curve falls "
	"below the model in the transition and the scatter region.",
	.n_params = 1,
	.param = { { "half_angle_deg", "deg", 90.0, 15.0, 90.0, 4 } },
	.k_bic = 1,
	.apply = apply,
	.geo_axis = DIAG_GEO_ACCEPT,
	.nodes = nodes,
	.n_nodes = (int)(sizeof(nodes) / sizeof(nodes[0])),
	.needs_baffle = 0,	/* the detector's own: any scene */
};
