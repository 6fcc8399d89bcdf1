/*
 * cause_knife_edge_radius.c - vane knife edges rounded (thesis §4: about
 * 0.05 mm from grinding) instead of perfectly sharp.  The fillet is a lit,
 * curved surface that sees the detector: a re-trace cause, traced on a
 * grid of radii with common random numbers and interpolated between.
 */
#include "diagnose/diag_cause.h"

static const double nodes[] = { 0.0, 0.03, 0.06, 0.1, 0.15, 0.2,
				0.3 };

static void apply(const double *p, struct diag_state *s)
{
	s->geo[DIAG_GEO_EDGE_RADIUS] = p[0];
}

const struct diag_cause diag_cause_knife_edge_radius = {
	.name = "knife_edge_radius",
	.kind = DIAG_RETRACE,
	.explanation =
	"The vane knife edges are rounded rather than sharp. Machining and "
	"grinding leave a fillet of some hundredths of a millimetre; the "
	"fillet is lit by the source at every angle and, being curved, "
	"always has a part that faces the detector, so it adds single-"
	"scatter light just outside the field (the transition and the "
	"first tens of degrees of the scatter region), where a sharp edge "
	"adds none.",
	.n_params = 1,
	.param = { { "radius_mm", "mm", 0.0, 0.0, 0.3, 3 } },
	.k_bic = 1,
	.apply = apply,
	.geo_axis = DIAG_GEO_EDGE_RADIUS,
	.nodes = nodes,
	.n_nodes = (int)(sizeof(nodes) / sizeof(nodes[0])),
	.needs_baffle = 0,	/* meshes: tracer/mesh_edges.c */
};
