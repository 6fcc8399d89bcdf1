/*
 * mesh.h - a triangle soup with one surface group per triangle: what the
 * parametric baffle builds, what the CAD importers fill and what
 * --export-obj writes.  Vertices are float, as Embree takes them.
 */
#ifndef TRACER_MESH_H
#define TRACER_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

#define TRACER_GROUP_MAX 64
#define TRACER_GROUP_NAME_MAX 32

struct tracer_mesh {
	size_t n_vert, cap_vert;
	float *vert;		/* 3 per vertex, mm */
	size_t n_tri, cap_tri;
	uint32_t *tri;		/* 3 vertex indices per triangle */
	uint8_t *group;		/* surface group of each triangle */
	size_t n_group;
	char group_name[TRACER_GROUP_MAX][TRACER_GROUP_NAME_MAX];
};

void tracer_mesh_init(struct tracer_mesh *m);
void tracer_mesh_free(struct tracer_mesh *m);

/* Index of a group by name, created when new; -1 and err when full. */
int tracer_mesh_group(struct tracer_mesh *m, const char *name,
		      struct stray_error *err);

/* Index of an existing group, or -1. */
int tracer_mesh_find_group(const struct tracer_mesh *m, const char *name);

/* Append a vertex; its index goes to *idx. */
int tracer_mesh_add_vertex(struct tracer_mesh *m, double x, double y,
			   double z, uint32_t *idx, struct stray_error *err);

/* Append a triangle of existing vertices to a group. */
int tracer_mesh_add_triangle(struct tracer_mesh *m, uint32_t a, uint32_t b,
			     uint32_t c, int group, struct stray_error *err);

/* Total area of a group's triangles, mm^2. */
double tracer_mesh_group_area(const struct tracer_mesh *m, int group);

#endif /* TRACER_MESH_H */
