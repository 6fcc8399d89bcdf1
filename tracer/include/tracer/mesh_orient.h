/*
 * mesh_orient.h - the winding of a CAD mesh found and made outward
 * (issue 23 item 4).
 *
 * Exporters disagree on winding: an STL wound inward, or a part with a
 * few faces turned, traces without a word, but the edge model
 * (mesh_edges.c: convex edges, outward normals) and the exports then
 * change silently.  Triangles are joined into parts by the edges they
 * share (vertices matched by position, so parts split across groups or
 * files still join); each part is made consistent (the minority of its
 * triangles turned), and a closed part whose signed volume is negative
 * is turned as a whole.  A part that cannot be made consistent (a
 * Moebius-like strip, or edges wound both ways around a loop) is refused.
 */
#ifndef TRACER_MESH_ORIENT_H
#define TRACER_MESH_ORIENT_H

#include <stddef.h>

#include "stray/error.h"
#include "tracer/mesh.h"

struct tracer_orient_report {
	size_t parts;		/* joined by shared edges */
	size_t closed_parts;	/* every edge shared by exactly two */
	size_t turned_inconsistent;	/* triangles against their part */
	size_t inward_parts;	/* closed parts wound inward, turned */
	size_t turned_inward;	/* their triangles */
	size_t open_edges;	/* edges of one triangle (open parts) */
	size_t nonmanifold_edges;	/* edges of three or more, not used */
};

/*
 * Orient m's triangles outward in place and say what was done.
 * STRAY_EINVAL (naming the count) when a part cannot be oriented.
 */
int tracer_mesh_orient(struct tracer_mesh *m, struct tracer_orient_report *r,
		       struct stray_error *err);

#endif /* TRACER_MESH_ORIENT_H */
