/*
 * fuzz_mesh_file.c - libFuzzer target for a mesh file named by a scene:
 * the byte count pre-scan (tracer_mesh_prescan, issue 31) and then, when
 * it passes, the import through assimp into our mesh.  The first byte
 * picks the name the bytes are written under (even: m.obj, odd: m.stl;
 * assimp picks the reader by extension), the rest are the file.
 */
#define _GNU_SOURCE
#include "fuzz_mesh.h"
#include "stray/errfmt.h"
#include "tracer/mesh.h"
#include "tracer/mesh_import.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc;
	(void)argv;
	fuzz_mesh_init("fuzz_mesh");
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct tracer_mesh m;
	struct stray_error err;
	char path[128], line[1024];

	if (size < 1)
		return 0;
	fuzz_mesh_write(data + 1, size - 1, data[0], path, sizeof(path));
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
