/*
 * scene_load.h - a scene by name: `ref4` (the built-in parametric baffle,
 * with `key=value` overrides) or a scene file.
 */
#ifndef TRACER_SCENE_LOAD_H
#define TRACER_SCENE_LOAD_H

#include "stray/error.h"
#include "tracer/scene.h"

/* Fill s (initialised, not committed); sets are `key=value` overrides. */
int tracer_scene_load(const char *name, const char *const *sets, int n_sets,
		      struct tracer_scene *s, struct stray_error *err);

#endif /* TRACER_SCENE_LOAD_H */
