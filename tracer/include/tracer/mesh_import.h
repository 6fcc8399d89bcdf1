/*
 * mesh_import.h - CAD meshes into the tracer's mesh: Wavefront OBJ and
 * STL (ASCII and binary), read by the Open Asset Import Library (assimp).
 * Each OBJ group (`g`, else its `usemtl` material) becomes a surface
 * group; a file without groups (STL) goes to one named group.
 */
#ifndef TRACER_MESH_IMPORT_H
#define TRACER_MESH_IMPORT_H

#include <stddef.h>

#include "stray/error.h"
#include "tracer/mesh.h"

/*
 * Append the triangles of path to m, scaled by scale_mm (file units to
 * mm).  group: when not NULL, every triangle goes to this group.
 * Errors name the file and say what the importer found wrong.
 */
int tracer_mesh_import(struct tracer_mesh *m, const char *path,
		       const char *group, double scale_mm,
		       struct stray_error *err);

/* Input limit (docs/limits.md): triangles in one scene. */
#define TRACER_MESH_TRI_MAX 5000000u

/*
 * The size of path counted from its bytes, before any import (binary
 * STL's declared count; OBJ faces and vertices, ASCII STL facets, by one
 * streaming pass): more than TRACER_MESH_TRI_MAX - tri_before triangles,
 * or more than 3 x that many vertices, is refused (STRAY_EINVAL) in
 * constant memory.  Unreadable files pass (the importer names them).
 */
int tracer_mesh_prescan(const char *path, size_t tri_before,
			struct stray_error *err);

#endif /* TRACER_MESH_IMPORT_H */
