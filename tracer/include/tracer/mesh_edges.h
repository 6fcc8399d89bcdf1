/*
 * mesh_edges.h - knife edges of a CAD mesh through a physical edge model
 * (issue 17 item 2): sharp edges found by the dihedral angle of their two
 * triangles, each rounded into a fillet of radius r tangent to both faces
 * (the same fillet tracer/baffle.c builds on the parametric vanes).
 */
#ifndef TRACER_MESH_EDGES_H
#define TRACER_MESH_EDGES_H

#include "stray/error.h"
#include "tracer/scene.h"

/* Edges whose faces meet at an interior (material) angle below this are
 * knife edges: 45 deg bevels and 90 deg corners of vanes, not the facets
 * of a revolved surface. */
#define TRACER_EDGE_MAX_WEDGE_DEG 100.0

/* Round every knife edge of s's mesh to radius r mm (r = 0: nothing);
 * new triangles join the group "<group>_edge" of the edge's first face,
 * with that face's material. */
int tracer_mesh_round_edges(struct tracer_scene *s, double r,
			    struct stray_error *err);

#endif /* TRACER_MESH_EDGES_H */
