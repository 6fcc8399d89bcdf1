/*
 * section.c - the drawing of the design: the traced scene's mesh (the
 * OBJ `stray trace --export-obj` writes, so vane files, the built-in
 * ref4 and CAD meshes are drawn the same way, from what is traced) cut
 * by the plane y = 0 through the axis, drawn with PLplot in mm.
 */
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "review/review.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define SECTION_VERTS_MAX 4000000	/* the tracer's own meshes: far fewer */

struct mesh_cut {
	double (*v)[3];
	size_t nv, cap;
	double *seg;	/* x0 z0 x1 z1 per segment */
	size_t ns, scap;
	double lo[2], hi[2];
};

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
	void *q;
	size_t c = *cap ? *cap : 1024;

	if (need <= *cap)
		return 1;
	while (c < need)
		c *= 2;
	if (!(q = realloc(*p, c * size)))
		return 0;
	*p = q;
	*cap = c;
	return 1;
}

/* The segment where triangle (a, b, c) crosses y = 0, if it does. */
static int cut(struct mesh_cut *m, const double *a, const double *b,
	       const double *c)
{
	const double *t[3] = { a, b, c };
	double pt[4];
	int k, n = 0;

	for (k = 0; k < 3 && n < 2; k++) {
		const double *p = t[k], *q = t[(k + 1) % 3];

		if ((p[1] < 0.0) == (q[1] < 0.0))
			continue;
		double f = p[1] / (p[1] - q[1]);

		pt[2 * n] = p[0] + f * (q[0] - p[0]);
		pt[2 * n + 1] = p[2] + f * (q[2] - p[2]);
		n++;
	}
	if (n < 2)
		return 1;
	if (!grow((void **)&m->seg, &m->scap, 4 * (m->ns + 1), sizeof(double)))
		return 0;
	memcpy(m->seg + 4 * m->ns++, pt, sizeof(pt));
	for (k = 0; k < 4; k++) {
		if (pt[k] < m->lo[k & 1])
			m->lo[k & 1] = pt[k];
		if (pt[k] > m->hi[k & 1])
			m->hi[k & 1] = pt[k];
	}
	return 1;
}

static int read_obj(const char *obj, struct mesh_cut *m, struct stray_error *err)
{
	FILE *f = fopen(obj, "r");
	char line[512];
	long lineno = 0, ia, ib, ic;

	if (!f)
		return stray_error_at(err, STRAY_ENOTFOUND, obj, 0, NULL,
				      "scene mesh not found");
	m->lo[0] = m->lo[1] = 1e300;
	m->hi[0] = m->hi[1] = -1e300;
	while (fgets(line, sizeof(line), f)) {
		lineno++;
		if (line[0] == 'v' && line[1] == ' ') {
			if (m->nv >= SECTION_VERTS_MAX ||
			    !grow((void **)&m->v, &m->cap, m->nv + 1, sizeof(*m->v)))
				goto too_big;
			if (sscanf(line + 2, "%lf %lf %lf", &m->v[m->nv][0],
				   &m->v[m->nv][1], &m->v[m->nv][2]) != 3)
				goto bad;
			m->nv++;
		} else if (line[0] == 'f' && line[1] == ' ') {
			if (sscanf(line + 2, "%ld %ld %ld", &ia, &ib, &ic) != 3 ||
			    ia < 1 || ib < 1 || ic < 1 || (size_t)ia > m->nv ||
			    (size_t)ib > m->nv || (size_t)ic > m->nv)
				goto bad;
			if (!cut(m, m->v[ia - 1], m->v[ib - 1], m->v[ic - 1]))
				goto too_big;
		}
	}
	fclose(f);
	if (!m->ns)
		return stray_error_at(err, STRAY_EINVAL, obj, 0, NULL,
				      "the mesh does not cross the plane y = 0");
	return STRAY_OK;
bad:
	fclose(f);
	return stray_error_at(err, STRAY_EPARSE, obj, lineno, NULL,
			      "not a triangle-mesh OBJ line");
too_big:
	fclose(f);
	return stray_error_at(err, STRAY_ENOMEM, obj, lineno, NULL,
			      "mesh too large to draw");
}

int review_draw_section(const char *obj, const char *png,
			struct stray_error *err)
{
	struct mesh_cut m;
	struct stray_file_out out;
	struct stat st;
	double pad;
	size_t i;
	int rc;

	memset(&m, 0, sizeof(m));
	if ((rc = read_obj(obj, &m, err)) != STRAY_OK)
		goto done;
	if ((rc = stray_file_open_atomic(&out, png, err)) != STRAY_OK)
		goto done;
	pad = 0.05 * ((m.hi[0] - m.lo[0]) > (m.hi[1] - m.lo[1]) ?
		      m.hi[0] - m.lo[0] : m.hi[1] - m.lo[1]) + 1e-3;
	plsdev("pngcairo");
	plsfnam(out.tmp);
	plsetopt("geometry", "900x700");
	plscolbg(255, 255, 255);
	plscol0(1, 0, 0, 0);	/* black frame and labels */
	plscol0(9, 30, 60, 200);
	plinit();
	plcol0(1);
	plenv(m.lo[0] - pad, m.hi[0] + pad, m.lo[1] - pad, m.hi[1] + pad, 1, 0);
	pllab("x [mm]", "z [mm] (boresight +z)", "section of the traced scene at y = 0");
	plcol0(9);
	for (i = 0; i < m.ns; i++)
		pljoin(m.seg[4 * i], m.seg[4 * i + 1], m.seg[4 * i + 2],
		       m.seg[4 * i + 3]);
	plend();
	if (stat(out.tmp, &st) != 0 || st.st_size == 0) {
		stray_file_abort(&out);
		rc = stray_error_at(err, STRAY_EIO, png, 0, "plot", "PLplot wrote no file");
	} else {
		rc = stray_file_commit(&out, err);
	}
done:
	free(m.v);
	free(m.seg);
	return rc;
}
