/*
 * scene_load.c - scenes by name: the built-in `ref4` baffle, or a JSON
 * scene file: a vane baffle of the parametric family ("type": "vanes") or
 * meshes with the material of each surface group.
 */
#include <string.h>

#include "stray/errfmt.h"
#include "tracer/baffle.h"
#include "tracer/scene_load.h"
#include "tracer/scene_file.h"

int tracer_scene_load(const char *name, const char *const *sets, int n_sets,
		      struct tracer_scene *s, struct stray_error *err)
{
	struct tracer_baffle b;
	int i, rc;

	/* a scene file takes its own overrides: any baffle key for a
	 * "vanes" file, the mesh-level keys for a mesh scene */
	if (strcmp(name, "ref4") != 0)
		return tracer_scene_file_load_sets(name, sets, n_sets, s, err);
	tracer_baffle_ref4(&b);
	for (i = 0; i < n_sets; i++) {
		rc = tracer_baffle_set(&b, sets[i], err);
		if (rc)
			return rc;
	}
	return tracer_baffle_build(&b, s, err);
}
