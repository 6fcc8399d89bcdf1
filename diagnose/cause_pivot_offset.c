/*
 * cause_pivot_offset.c - the rotation stage turns the baffle about a point
 * behind the entrance aperture instead of its centre.  In the baffle's
 * frame the collimated beam's axis then passes through the pivot, so the
 * beam is displaced across the aperture by d sin(theta): a re-trace with
 * the beam centre moved by d along the boresight (one trace serves every
 * angle), on a grid of offsets.
 */
#include "diagnose/diag_cause.h"

/* dense where the beam starts to leave the aperture, sparse beyond */
static const double nodes[] = { 0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0,
				20.0 };

static void apply(const double *p, struct diag_state *s)
{
	s->geo[DIAG_GEO_PIVOT] = p[0];
}

const struct diag_cause diag_cause_pivot_offset = {
	.name = "pivot_offset",
	.kind = DIAG_RETRACE,
	.explanation =
	"The rotation stage turns the baffle about a point offset along "
	"the boresight from the entrance aperture, so at angle theta the "
	"collimated beam is displaced across the aperture by d sin(theta). "
	"A beam that just fills the aperture then leaves a growing part of "
	"it unlit and lights the front of vane 1 and the rim instead, so "
	"the measured curve departs from the model increasingly with "
	"angle.",
	.n_params = 1,
	.param = { { "offset_mm", "mm", 0.0, 0.0, 20.0, 3 } },
	.k_bic = 1,
	.apply = apply,
	.geo_axis = DIAG_GEO_PIVOT,
	.nodes = nodes,
	.n_nodes = (int)(sizeof(nodes) / sizeof(nodes[0])),
	.needs_baffle = 0,
};
