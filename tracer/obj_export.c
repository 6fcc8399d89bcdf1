/*
 * obj_export.c - Wavefront OBJ writer (1-based indices, one group each).
 */
#include <stdio.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/obj_export.h"

static void write_group(FILE *f, const struct tracer_mesh *m, size_t g)
{
	size_t i, n = 0;

	for (i = 0; i < m->n_tri; i++)
		n += m->group[i] == g;
	if (n == 0)
		return;	/* importers drop empty groups anyway */
	fprintf(f, "g %s\nusemtl %s\n", m->group_name[g], m->group_name[g]);
	for (i = 0; i < m->n_tri; i++)
		if (m->group[i] == g)
			fprintf(f, "f %u %u %u\n", m->tri[3 * i] + 1,
				m->tri[3 * i + 1] + 1, m->tri[3 * i + 2] + 1);
}

int tracer_obj_export(const struct tracer_mesh *m, const char *path,
		      struct stray_error *err)
{
	struct stray_file_out out;
	FILE *f;
	size_t i;

	if (stray_file_open_atomic(&out, path, err) != STRAY_OK)
		return stray_error_set(err, STRAY_EIO, "--export-obj",
				       "cannot open for writing");
	f = out.f;
	fprintf(f, "# straylight tracer mesh; units mm; %zu triangles\n",
		m->n_tri);
	for (i = 0; i < m->n_vert; i++)
		fprintf(f, "v %.9g %.9g %.9g\n", m->vert[3 * i],
			m->vert[3 * i + 1], m->vert[3 * i + 2]);
	for (i = 0; i < m->n_group; i++)
		write_group(f, m, i);
	return stray_file_commit(&out, err);
}
