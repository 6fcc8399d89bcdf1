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

#endif /* TRACER_SCENE_FILE_H */
