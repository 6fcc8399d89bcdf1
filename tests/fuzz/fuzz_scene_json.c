/*
 * fuzz_scene_json.c - libFuzzer target for `stray trace --scene FILE.json`:
 * the scene file (cJSON: meshes, materials, groups, detector, beam) and the
 * meshes it names, read through assimp into our mesh.  The input is the
 * scene JSON, optionally followed by a NUL and the bytes of "m.obj"; the
 * scene's folder also holds a fixed cube.obj and tri.stl.  Names that reach
 * outside that folder (/dev, /proc, /sys, "..") are skipped: reading a
 * device is a limit for the loader, not a parse.
 */
#define _GNU_SOURCE
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "tracer/scene.h"
#include "tracer/scene_file.h"

static char dir[64];

static void put(const char *name, const void *p, size_t n)
{
	char path[128];
	FILE *f;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	f = fopen(path, "wb");
	if (!f)
		abort();
	if (n && fwrite(p, 1, n, f) != n)
		abort();
	fclose(f);
}

static void cleanup(void)
{
	static const char *names[] = { "scene.json", "m.obj", "cube.obj",
				       "tri.stl" };
	char path[128];
	size_t i;

	for (i = 0; i < sizeof(names) / sizeof(names[0]); i++) {
		snprintf(path, sizeof(path), "%s/%s", dir, names[i]);
		unlink(path);
	}
	rmdir(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	static const char cube[] =
		"v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
		"v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
		"g wall\nf 1 2 3\nf 1 3 4\nf 5 6 7\nf 5 7 8\n"
		"f 1 2 6\nf 1 6 5\nf 3 4 8\nf 3 8 7\n";
	static const char tri[] =
		"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
		"vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
	const char *tmp = getenv("TMPDIR");

	(void)argc;
	(void)argv;
	snprintf(dir, sizeof(dir), "%s/fuzz_scene.XXXXXX",
		 tmp && strlen(tmp) < 40 ? tmp : "/tmp");
	if (!mkdtemp(dir))
		abort();
	atexit(cleanup);
	put("cube.obj", cube, sizeof(cube) - 1);
	put("tri.stl", tri, sizeof(tri) - 1);
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static const char *outside[] = { "/dev", "/proc", "/sys", ".." };
	const uint8_t *nul = memchr(data, 0, size);
	size_t json = nul ? (size_t)(nul - data) : size;
	struct tracer_scene s;
	struct stray_error err;
	char path[128], line[1024];
	size_t i;

	for (i = 0; i < sizeof(outside) / sizeof(outside[0]); i++)
		if (memmem(data, size, outside[i], strlen(outside[i])))
			return 0;
	put("scene.json", data, json);
	put("m.obj", nul ? nul + 1 : data, nul ? size - json - 1 : 0);
	snprintf(path, sizeof(path), "%s/scene.json", dir);
	stray_error_clear(&err);
	tracer_scene_init(&s);
	if (tracer_scene_file_load(path, &s, &err) != 0)
		stray_error_format(&err, line, sizeof(line));
	tracer_scene_free(&s);
	return 0;
}
