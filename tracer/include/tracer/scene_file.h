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

#endif /* TRACER_SCENE_FILE_H */
