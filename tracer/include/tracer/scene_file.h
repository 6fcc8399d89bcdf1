/*
 * scene_file.h - a scene described in JSON: meshes (OBJ, STL), the
 * material of each surface group, the detector and the beam.
 */
#ifndef TRACER_SCENE_FILE_H
#define TRACER_SCENE_FILE_H

#include "stray/error.h"
#include "tracer/scene.h"

int tracer_scene_file_load(const char *path, struct tracer_scene *s,
			   struct stray_error *err);

/* The same with `key=value` overrides: any baffle key for a "vanes"
 * file; accept_half_angle_deg and edge_radius (the mesh edge model,
 * tracer/mesh_edges.c) for a mesh scene. */
int tracer_scene_file_load_sets(const char *path, const char *const *sets,
				int n_sets, struct tracer_scene *s,
				struct stray_error *err);

/* 1 when path is a scene file of "type": "vanes" (the parametric family),
 * 0 otherwise (a mesh scene, or unreadable: the load says why). */
int tracer_scene_file_is_vanes(const char *path);

/*
 * A CAD scene's checks once loaded (scene_checks.c): the winding made
 * outward (tracer/mesh_orient.h; what was turned said in s->note) and
 * the mesh's extent against its detector (a file in metres or inches is
 * refused with the scale_mm it needs).
 */
int tracer_scene_mesh_checks(const char *path, struct tracer_scene *s,
			     struct stray_error *err);

#endif /* TRACER_SCENE_FILE_H */
