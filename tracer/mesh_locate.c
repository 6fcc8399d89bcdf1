/*
 * mesh_locate.c - find the line or byte of a mesh file that made the
 * importer fail (see mesh_locate.h).  Formats: Wavefront OBJ (Wavefront
 * Technologies, "Object Files (.obj)", Advanced Visualizer manual, app.
 * B1) and STL (3D Systems, StereoLithography Interface Specification,
 * 1989): binary STL is an 80-byte header, a uint32 facet count and 50
 * bytes per facet.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/mesh_locate.h"

#define STL_HEADER 84u
#define STL_FACET 50u

/* Count the numbers that make up the rest of a line; -1 at a bad one. */
static int count_numbers(const char *s)
{
	int n = 0;

	for (;;) {
		char *end;
		double v;

		while (*s == ' ' || *s == '\t' || *s == '\r')
			s++;
		if (*s == '\0' || *s == '#')
			return n;
		v = strtod(s, &end);
		if (end == s || (*end && *end != ' ' && *end != '\t' &&
				 *end != '\r'))
			return -1;
		if (!isfinite(v))
			return -2;	/* assimp drops the mesh silently */
		s = end;
		n++;
	}
}

/* An OBJ face: every vertex reference v[/vt[/vn]] within 1..n_v (or a
 * relative -1..-n_v). */
static int face_ok(const char *s, long n_v)
{
	int refs = 0;

	for (;;) {
		char *end;
		long i;

		while (*s == ' ' || *s == '\t' || *s == '\r')
			s++;
		if (*s == '\0' || *s == '#')
			return refs >= 3;
		i = strtol(s, &end, 10);
		if (end == s || i == 0 || i > n_v || i < -n_v)
			return 0;
		s = end;
		while (*s && *s != ' ' && *s != '\t' && *s != '\r')
			s++;	/* the /vt/vn part is not checked */
		refs++;
	}
}

/* The first suspicious line of an OBJ or ASCII STL text, or 0; *why is
 * set when the line has a non-finite coordinate. */
static long bad_text_line(char *text, const char **why)
{
	long line = 0, n_v = 0;
	char *s = text;

	while (s) {
		char *nl = strchr(s, '\n'), *t = s;

		if (nl)
			*nl = '\0';
		line++;
		while (*t == ' ' || *t == '\t')
			t++;
		if (!strncmp(t, "v ", 2)) {
			int k = count_numbers(t + 2);

			if (k == -2)
				*why = "a vertex coordinate is not a finite number";
			if (k < 3)
				return line;
			n_v++;
		} else if (!strncmp(t, "vn ", 3) || !strncmp(t, "vt ", 3)) {
			if (count_numbers(t + 3) < 2)
				return line;
		} else if (!strncmp(t, "f ", 2)) {
			if (!face_ok(t + 2, n_v))
				return line;
		} else if (!strncmp(t, "vertex", 6)) {		/* ASCII STL */
			if (count_numbers(t + 6) != 3)
				return line;
		} else if (!strncmp(t, "facet normal", 12)) {
			if (count_numbers(t + 12) != 3)
				return line;
		}
		s = nl ? nl + 1 : NULL;
	}
	return 0;
}

/* A binary STL whose declared facets do not fit: the byte it ends at. */
static int binary_stl_short(const unsigned char *b, size_t len, char *msg,
			    size_t size)
{
	uint32_t n;
	uint64_t need;

	if (len < STL_HEADER || !memchr(b, '\0', len))
		return 0;
	n = (uint32_t)b[80] | (uint32_t)b[81] << 8 | (uint32_t)b[82] << 16 |
	    (uint32_t)b[83] << 24;
	need = STL_HEADER + (uint64_t)STL_FACET * n;
	if (need == len)
		return 0;
	snprintf(msg, size, "byte %zu: %lu facets declared need %llu bytes",
		 len < need ? len : (size_t)need, (unsigned long)n,
		 (unsigned long long)need);
	return 1;
}

void tracer_mesh_locate(const char *path, struct stray_error *err)
{
	char *text, msg[STRAY_ERROR_TEXT_MAX];
	size_t len;
	struct stray_error io;

	stray_error_clear(&io);
	if (!err || stray_file_read(path, &text, &len, &io) != STRAY_OK)
		return;
	if (binary_stl_short((const unsigned char *)text, len, msg,
			     sizeof(msg))) {
		err->text[0] = '\0';
		stray_error_text(err, msg);
	} else if (!memchr(text, '\0', len)) {
		const char *why = NULL;

		stray_error_locate(err, NULL, bad_text_line(text, &why));
		if (why) {	/* say so, not assimp's "No meshes remaining" */
			err->reason = why;
			err->text[0] = '\0';
		}
	}
	free(text);
}
