/*
 * fuzz_mesh_prescan.c - libFuzzer target for the mesh byte count alone
 * (tracer_mesh_prescan, issue 31), thousands of runs a second where
 * fuzz_mesh_file (with assimp) does ~35: the first byte picks the name
 * (even: m.obj, odd: m.stl), the rest are the file; tri_before from the
 * second byte puts the limit near the counts a small input reaches.
 */
#define _GNU_SOURCE
#include "fuzz_mesh.h"
#include "stray/errfmt.h"
#include "tracer/mesh_import.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc;
	(void)argv;
	fuzz_mesh_init("fuzz_prescan");
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_error err;
	char path[128], line[1024];

	if (size < 2)
		return 0;
	fuzz_mesh_write(data + 2, size - 2, data[0], path, sizeof(path));
	stray_error_clear(&err);
	if (tracer_mesh_prescan(path, TRACER_MESH_TRI_MAX - data[1], &err))
		stray_error_format(&err, line, sizeof(line));
	return 0;
}
