/*
 * test_mesh_prescan.c - a mesh's triangles counted from its bytes before
 * assimp (tracer/mesh_import.h): OBJ polygons as k - 2 triangles, ASCII
 * STL facets, binary STL's declared count, each against what the scene
 * has left under the 5 M limit.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "stray/errfmt.h"
#include "tracer/mesh_import.h"

static char path[64];

static const char *put(const char *ext, const void *bytes, size_t n)
{
	FILE *f;

	snprintf(path, sizeof(path), "/tmp/stray_prescan_%d.%s",
		 (int)getpid(), ext);
	f = fopen(path, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(bytes, 1, n, f), n);
	fclose(f);
	return path;
}

static int scan(size_t before, struct stray_error *err)
{
	stray_error_clear(err);
	return tracer_mesh_prescan(path, before, err);
}

static void test_obj_polygons(void **state)
{
	/* a quad (2 triangles) and a triangle: 3 */
	static const char obj[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
		"f 1 2 3 4\n\tf 1 2 3\r\n# f 1 2 3\nfoo 1 2 3\n";
	struct stray_error err;

	(void)state;
	put("obj", obj, sizeof(obj) - 1);
	assert_int_equal(scan(TRACER_MESH_TRI_MAX - 3, &err), STRAY_OK);
	assert_int_equal(scan(TRACER_MESH_TRI_MAX - 2, &err), STRAY_EINVAL);
	assert_string_equal(err.field, "triangles");
	unlink(path);
}

static void test_stl(void **state)
{
	static const char ascii[] = "solid x\n facet normal 0 0 1\n"
		"  outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex 0 1 0\n"
		" endloop\n endfacet\nendsolid x\n";
	unsigned char bin[84 + 2 * 50] = { 0 };
	struct stray_error err;

	(void)state;
	put("stl", ascii, sizeof(ascii) - 1);
	assert_int_equal(scan(TRACER_MESH_TRI_MAX - 1, &err), STRAY_OK);
	assert_int_equal(scan(TRACER_MESH_TRI_MAX, &err), STRAY_EINVAL);
	bin[80] = 2;
	memcpy(bin, "solid but binary", 16);	/* some exporters do */
	put("stl", bin, sizeof(bin));
	assert_int_equal(scan(TRACER_MESH_TRI_MAX - 2, &err), STRAY_OK);
	assert_int_equal(scan(TRACER_MESH_TRI_MAX - 1, &err), STRAY_EINVAL);
	/* 4e9 declared in a short file: the limit first, in microseconds */
	memset(bin, 0, 16);
	bin[80] = bin[81] = bin[82] = bin[83] = 0xff;
	put("stl", bin, sizeof(bin));
	assert_int_equal(scan(0, &err), STRAY_EINVAL);
	unlink(path);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_obj_polygons),
		cmocka_unit_test(test_stl),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
