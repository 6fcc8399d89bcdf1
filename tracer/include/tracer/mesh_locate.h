/*
 * mesh_locate.h - where in a mesh file the importer's failure lies.
 *
 * assimp says what is wrong with an OBJ or STL file but not where.  When
 * an import fails, this looks again at the file with checks of its own
 * (it never builds geometry): for a binary STL the byte offset at which
 * the facets it declares run out; for OBJ and ASCII STL the first line
 * whose numbers or vertex indices cannot be right.
 */
#ifndef TRACER_MESH_LOCATE_H
#define TRACER_MESH_LOCATE_H

#include "stray/error.h"

/*
 * Add the place of a failed import of path to err: err->line for text
 * files, a byte offset in err->text for binary STL.  Leaves err as it is
 * when no culprit is found.
 */
void tracer_mesh_locate(const char *path, struct stray_error *err);

#endif /* TRACER_MESH_LOCATE_H */
