/*
 * fuzz_mesh_file.c - libFuzzer target for a mesh file named by a scene:
 * the byte count pre-scan (tracer_mesh_prescan, issue 31) and then, when
 * it passes, the import through assimp into our mesh.  The first byte
 * picks the name the bytes are written under (even: m.obj, odd: m.stl;
 * assimp picks the reader by extension), the rest are the file.
 */
#define _GNU_SOURCE
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "tracer/mesh.h"
#include "tracer/mesh_import.h"

static char dir[64];

static void cleanup(void)
{
	char path[128];

	snprintf(path, sizeof(path), "%s/m.obj", dir);
	unlink(path);
	snprintf(path, sizeof(path), "%s/m.stl", dir);
	unlink(path);
	rmdir(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	const char *tmp = getenv("TMPDIR");

	(void)argc;
	(void)argv;
	snprintf(dir, sizeof(dir), "%s/fuzz_mesh.XXXXXX",
		 tmp && strlen(tmp) < 40 ? tmp : "/tmp");
	if (!mkdtemp(dir))
		abort();
	atexit(cleanup);
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct tracer_mesh m;
	struct stray_error err;
	char path[128], line[1024];
	FILE *f;

	if (size < 1)
		return 0;
	snprintf(path, sizeof(path), "%s/m.%s", dir, data[0] & 1 ? "stl"
								 : "obj");
	if (!(f = fopen(path, "wb")))
		abort();
	if (size > 1 && fwrite(data + 1, 1, size - 1, f) != size - 1)
		abort();
	fclose(f);
	stray_error_clear(&err);
	if (tracer_mesh_prescan(path, 0, &err) != STRAY_OK) {
		stray_error_format(&err, line, sizeof(line));
		return 0;
	}
	tracer_mesh_init(&m);
	if (tracer_mesh_import(&m, path, NULL, 1.0, &err) != STRAY_OK)
		stray_error_format(&err, line, sizeof(line));
	tracer_mesh_free(&m);
	return 0;
}
