/*
 * fuzz_mesh_prescan.c - libFuzzer target for the mesh byte count alone
 * (tracer_mesh_prescan, issue 31), thousands of runs a second where
 * fuzz_mesh_file (with assimp) does ~35: the first byte picks the name
 * (even: m.obj, odd: m.stl), the rest are the file; tri_before from the
 * second byte puts the limit near the counts a small input reaches.
 */
#define _GNU_SOURCE
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
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
	snprintf(dir, sizeof(dir), "%s/fuzz_prescan.XXXXXX",
		 tmp && strlen(tmp) < 40 ? tmp : "/tmp");
	if (!mkdtemp(dir))
		abort();
	atexit(cleanup);
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct stray_error err;
	char path[128], line[1024];
	FILE *f;

	if (size < 2)
		return 0;
	snprintf(path, sizeof(path), "%s/m.%s", dir, data[0] & 1 ? "stl"
								 : "obj");
	if (!(f = fopen(path, "wb")))
		abort();
	if (size > 2 && fwrite(data + 2, 1, size - 2, f) != size - 2)
		abort();
	fclose(f);
	stray_error_clear(&err);
	if (tracer_mesh_prescan(path, TRACER_MESH_TRI_MAX - data[1], &err))
		stray_error_format(&err, line, sizeof(line));
	return 0;
}
