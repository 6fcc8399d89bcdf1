/*
 * fuzz_mesh.h - what the two mesh targets share (fuzz_mesh_file,
 * fuzz_mesh_prescan): a scratch folder made once, removed at exit, and
 * the input written there as m.obj or m.stl (the importer picks its
 * reader by extension).
 */
#ifndef STRAY_FUZZ_MESH_H
#define STRAY_FUZZ_MESH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char fuzz_mesh_dir[64];

static void fuzz_mesh_cleanup(void)
{
	char path[128];

	snprintf(path, sizeof(path), "%s/m.obj", fuzz_mesh_dir);
	unlink(path);
	snprintf(path, sizeof(path), "%s/m.stl", fuzz_mesh_dir);
	unlink(path);
	rmdir(fuzz_mesh_dir);
}

/* The scratch folder, under $TMPDIR when that is short. */
static void fuzz_mesh_init(const char *stem)
{
	const char *tmp = getenv("TMPDIR");

	snprintf(fuzz_mesh_dir, sizeof(fuzz_mesh_dir), "%s/%s.XXXXXX",
		 tmp && strlen(tmp) < 40 ? tmp : "/tmp", stem);
	if (!mkdtemp(fuzz_mesh_dir))
		abort();
	atexit(fuzz_mesh_cleanup);
}

/* data written to m.stl (odd is_stl) or m.obj; its path in path. */
static void fuzz_mesh_write(const uint8_t *data, size_t size, int is_stl,
			    char *path, size_t path_size)
{
	FILE *f;

	snprintf(path, path_size, "%s/m.%s", fuzz_mesh_dir,
		 is_stl & 1 ? "stl" : "obj");
	if (!(f = fopen(path, "wb")))
		abort();
	if (size > 0 && fwrite(data, 1, size, f) != size)
		abort();
	fclose(f);
}

#endif /* STRAY_FUZZ_MESH_H */
