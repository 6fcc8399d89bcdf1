/*
 * mesh_prescan.c - a mesh's size counted from its bytes before assimp
 * sees it (issue 31): a 48 MB OBJ of 6 M faces took 1.84 GB and 15 s of
 * import before the 5 M-triangle limit (docs/limits.md) refused it.
 *
 * Binary STL declares its triangle count (uint32 at byte 80) and is
 * exactly 84 + 50 n bytes; text meshes are streamed once in constant
 * memory: OBJ "f" lines (a polygon of k corners is k - 2 triangles once
 * triangulated) and "v" lines, ASCII STL "facet" lines.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "stray/errfmt.h"
#include "stray/sizes.h"
#include "tracer/mesh_import.h"

/* The line scanner's state across buffer refills. */
struct scan {
	char first[8];		/* the first token of the line, truncated */
	size_t first_len;
	int tokens;		/* tokens on the line so far */
	int in_tok;
	size_t tri, vert;
};

static void end_line(struct scan *s)
{
	if (s->first_len == 1 && s->first[0] == 'f' && s->tokens >= 4)
		s->tri += (size_t)s->tokens - 3;	/* k corners: k - 2 */
	else if (s->first_len == 1 && s->first[0] == 'v')
		s->vert++;
	else if (s->first_len == 5 && memcmp(s->first, "facet", 5) == 0)
		s->tri++;
	s->first_len = 0;
	s->tokens = 0;
	s->in_tok = 0;
}

static void scan_bytes(struct scan *s, const char *p, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++) {
		char c = p[i];

		if (c == '\n') {
			end_line(s);
		} else if (c == ' ' || c == '\t' || c == '\r') {
			s->in_tok = 0;
		} else {
			if (!s->in_tok) {
				s->in_tok = 1;
				s->tokens++;
			}
			if (s->tokens == 1 && s->first_len < sizeof(s->first))
				s->first[s->first_len++] = c;
			else if (s->tokens == 1)	/* too long: no keyword */
				s->first_len = sizeof(s->first) + 1;
		}
	}
}

/* at_least: the scan stopped early; count is a lower bound. */
static int too_many(const char *path, const char *what, size_t count,
		    size_t limit, int at_least, struct stray_error *err)
{
	char text[64];
	int rc = stray_size_check(count, 1, limit, SIZE_MAX, path, what, NULL,
				  err);

	if (rc != STRAY_OK) {
		snprintf(text, sizeof(text), "%s%zu", at_least ? "at least "
			 : "", count);
		stray_error_text(err, text);
	}
	return rc;
}

int tracer_mesh_prescan(const char *path, size_t tri_before,
			struct stray_error *err)
{
	size_t tri_left = tri_before < TRACER_MESH_TRI_MAX
			  ? TRACER_MESH_TRI_MAX - tri_before : 0;
	unsigned char head[84];
	static char buf[1 << 16];
	struct scan s;
	struct stat st;
	size_t n;
	FILE *f = fopen(path, "rb");
	int rc, early = 0;

	if (!f || fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
		if (f)
			fclose(f);
		return STRAY_OK;	/* the importer names what is wrong */
	}
	n = fread(head, 1, sizeof(head), f);
	if (n == sizeof(head)) {
		uint32_t tri = (uint32_t)head[80] | (uint32_t)head[81] << 8 |
			       (uint32_t)head[82] << 16 |
			       (uint32_t)head[83] << 24;
		size_t len = strlen(path);
		int stl = len > 4 && strcasecmp(path + len - 4, ".stl") == 0;

		/* binary STL (its header may begin "solid" too: some
		 * exporters): the declared count against the limit */
		if ((uint64_t)st.st_size == 84 + 50 * (uint64_t)tri ||
		    (stl && memcmp(head, "solid", 5) != 0)) {
			/* (a count past the bytes there are is left to the
			 * importer, which names the byte offset) */
			fclose(f);
			return too_many(path, "triangles", tri, tri_left, 0,
					err);
		}
	}
	memset(&s, 0, sizeof(s));
	scan_bytes(&s, (const char *)head, n);
	while ((n = fread(buf, 1, sizeof(buf), f)) > 0) {
		scan_bytes(&s, buf, n);
		/* refuse as soon as the count is out, not at the end */
		if (s.tri > tri_left || s.vert > 3 * (size_t)TRACER_MESH_TRI_MAX) {
			early = 1;
			break;
		}
	}
	fclose(f);
	end_line(&s);
	rc = too_many(path, "triangles", s.tri, tri_left, early, err);
	if (rc == STRAY_OK)
		rc = too_many(path, "vertices", s.vert,
			      3 * (size_t)TRACER_MESH_TRI_MAX, early, err);
	return rc;
}
