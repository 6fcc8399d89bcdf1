/*
 * obj_export.h - write a scene's mesh as Wavefront OBJ, one group (`g`,
 * `usemtl`) per surface group, so other tracers (the Mitsuba peer) and
 * CAD tools see the same geometry.
 */
#ifndef TRACER_OBJ_EXPORT_H
#define TRACER_OBJ_EXPORT_H

#include "stray/error.h"
#include "tracer/mesh.h"

int tracer_obj_export(const struct tracer_mesh *m, const char *path,
		      struct stray_error *err);

#endif /* TRACER_OBJ_EXPORT_H */
