/*
 * mesh_import.c - OBJ and STL through assimp's C API (cimport.h).
 * Triangulate and join identical vertices so that shared edges stay
 * shared (watertight for Embree's robust mode); node transforms are not
 * applied (OBJ and STL have none).
 */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/mesh_import.h"
#include "tracer/mesh_locate.h"


/* The surface group of one assimp mesh: forced, OBJ group, material. */
static const char *group_of(const struct aiScene *sc,
			    const struct aiMesh *am, const char *forced,
			    struct aiString *buf)
{
	if (forced)
		return forced;
	if (am->mName.length > 0 && strcmp(am->mName.data, "defaultobject"))
		return am->mName.data;
	if (am->mMaterialIndex < sc->mNumMaterials &&
	    aiGetMaterialString(sc->mMaterials[am->mMaterialIndex],
				AI_MATKEY_NAME, buf) == aiReturn_SUCCESS &&
	    buf->length > 0)
		return buf->data;
	return "default";
}

static int add_mesh(struct tracer_mesh *m, const struct aiMesh *am,
		    int group, double scale, struct stray_error *err)
{
	uint32_t base = (uint32_t)m->n_vert, idx;
	unsigned i;
	int rc = STRAY_OK;

	if (m->n_tri + am->mNumFaces > TRACER_MESH_TRI_MAX)	/* docs/limits.md */
		return stray_error_set_value(err, STRAY_EINVAL, "mesh",
			"more than 5000000 triangles in the scene",
			(double)(m->n_tri + am->mNumFaces));
	for (i = 0; i < am->mNumVertices && !rc; i++)
		rc = tracer_mesh_add_vertex(m, scale * am->mVertices[i].x,
					    scale * am->mVertices[i].y,
					    scale * am->mVertices[i].z, &idx,
					    err);
	for (i = 0; i < am->mNumFaces && !rc; i++) {
		const struct aiFace *f = &am->mFaces[i];

		if (f->mNumIndices != 3)
			continue;	/* points and lines carry no area */
		rc = tracer_mesh_add_triangle(m, base + f->mIndices[0],
					      base + f->mIndices[1],
					      base + f->mIndices[2], group, err);
	}
	return rc;
}

int tracer_mesh_import(struct tracer_mesh *m, const char *path,
		       const char *group, double scale_mm,
		       struct stray_error *err)
{
	const struct aiScene *sc;
	size_t before = m->n_tri;
	unsigned i;
	int rc = STRAY_OK;

	{	/* the one input limit for files: no 20 GB mesh into assimp */
		struct stat st;

		if (stat(path, &st) == 0 && (!S_ISREG(st.st_mode) ||
					     st.st_size > STRAY_FILE_READ_MAX))
			return stray_error_at(err, STRAY_EINVAL, path, 0, "mesh",
				S_ISREG(st.st_mode) ? "larger than the 256 MiB "
				"input limit (docs/limits.md)"
				: "is not a regular file");
	}
	/* counted before assimp takes gigabytes (issue 31) */
	if ((rc = tracer_mesh_prescan(path, m->n_tri, err)) != STRAY_OK)
		return rc;
	stray_file_note_input(path);	/* no output of the run may replace it */
	sc = aiImportFile(path, aiProcess_Triangulate |
				aiProcess_JoinIdenticalVertices |
				aiProcess_FindInvalidData);
	if (!sc) {
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "mesh",
				    aiGetErrorString()[0] ? "cannot import"
							  : "unreadable");
		stray_error_text(err, aiGetErrorString());
		tracer_mesh_locate(path, err);
		return rc;
	}
	for (i = 0; i < sc->mNumMeshes && !rc; i++) {
		struct aiString buf;
		int g = tracer_mesh_group(m, group_of(sc, sc->mMeshes[i],
						      group, &buf), err);

		rc = g < 0 ? STRAY_EINVAL : add_mesh(m, sc->mMeshes[i], g,
						  scale_mm, err);
	}
	aiReleaseImport(sc);
	if (!rc && m->n_tri == before)
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "mesh",
				    "has no triangles");
	if (rc && err)
		stray_error_locate(err, path, 0);
	return rc;
}
