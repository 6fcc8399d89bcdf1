/*
 * mesh_edges.c - knife edges of a CAD mesh rounded into fillets (issue 17
 * item 2), the physical edge model of the parametric vanes carried over
 * to any mesh:
 *   1. weld vertices by position (importers split them per group);
 *   2. an edge of exactly two triangles is a knife edge when it is convex
 *      (each face lies behind the other's plane; outward normals, the
 *      winding the exporters keep) and the material wedge between the
 *      faces, w = 180 deg - angle(n1, n2), is below
 *      TRACER_EDGE_MAX_WEDGE_DEG;
 *   3. at every vertex of a knife edge the fillet of radius r tangent to
 *      both faces replaces the tip: the faces' triangles are cut back to
 *      the tangent points, len = r / tan(w / 2) from the tip along each
 *      face (material removed, as tracer/baffle.c's fillet), and a strip
 *      of cylinder arcs joins them; arcs are per vertex (directions and
 *      normals averaged over the vertex's knife edges), so the strips of
 *      neighbouring edges share their vertices and the surface stays
 *      closed.
 * The strip is a thin rounded surface whose width (r (180 deg - w)) is
 * set by the radius: lit at every angle, part of it always facing the
 * detector, as on a ground vane.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tracer/mesh_edges.h"
#include "tracer/vec.h"

#define ARC_SEG 8
#define WELD_MM 1e-4

struct edge {
	uint32_t a, b;		/* welded vertex ids, a < b */
	uint32_t tri;
};

struct tip {			/* per welded vertex on a knife edge */
	struct vec3 e, n1, n2;	/* edge direction, face normals (sums) */
	struct vec3 c;		/* fillet centre */
	int count, group;
	uint32_t v1, v2, arc;	/* new vertices: cut-back tips, arc base */
};

static struct vec3 vert(const struct tracer_mesh *m, uint32_t i)
{
	return v3(m->vert[3 * i], m->vert[3 * i + 1], m->vert[3 * i + 2]);
}

static struct vec3 tri_normal(const struct tracer_mesh *m, size_t t)
{
	struct vec3 a = vert(m, m->tri[3 * t]), b = vert(m, m->tri[3 * t + 1]);
	struct vec3 c = vert(m, m->tri[3 * t + 2]);

	return v3_norm(v3_cross(v3_sub(b, a), v3_sub(c, a)));
}

static struct vec3 tri_centroid(const struct tracer_mesh *m, size_t t)
{
	struct vec3 a = vert(m, m->tri[3 * t]), b = vert(m, m->tri[3 * t + 1]);
	struct vec3 c = vert(m, m->tri[3 * t + 2]);

	return v3_scale(v3_add(v3_add(a, b), c), 1.0 / 3.0);
}

static const struct tracer_mesh *sort_mesh;

static int cmp_pos(const void *x, const void *y)
{
	uint32_t i = *(const uint32_t *)x, j = *(const uint32_t *)y;
	int k;

	for (k = 0; k < 3; k++) {
		double a = floor(sort_mesh->vert[3 * i + k] / WELD_MM + 0.5);
		double b = floor(sort_mesh->vert[3 * j + k] / WELD_MM + 0.5);

		if (a != b)
			return a < b ? -1 : 1;
	}
	return (i > j) - (i < j);
}

/* weld[i]: the smallest vertex index at i's (rounded) position. */
static int weld(const struct tracer_mesh *m, uint32_t *weld_of)
{
	uint32_t *order = malloc(m->n_vert * sizeof(*order));
	size_t i, start = 0;

	if (!order)
		return -1;
	for (i = 0; i < m->n_vert; i++)
		order[i] = (uint32_t)i;
	sort_mesh = m;
	qsort(order, m->n_vert, sizeof(*order), cmp_pos);
	/* runs of one (rounded) position weld to the run's first index */
	for (i = 1, start = 0; i < m->n_vert; i++) {
		uint32_t p = order[i - 1], q = order[i];
		int same = 1, k;

		for (k = 0; k < 3; k++)
			same &= floor(m->vert[3 * p + k] / WELD_MM + 0.5) ==
				floor(m->vert[3 * q + k] / WELD_MM + 0.5);
		if (!same)
			start = i;
		weld_of[q] = order[start];
	}
	if (m->n_vert)
		weld_of[order[0]] = order[0];
	free(order);
	return 0;
}

static int cmp_edge(const void *x, const void *y)
{
	const struct edge *p = x, *q = y;

	if (p->a != q->a)
		return p->a < q->a ? -1 : 1;
	if (p->b != q->b)
		return p->b < q->b ? -1 : 1;
	return (p->tri > q->tri) - (p->tri < q->tri);
}

/* Is the shared edge of triangles t1, t2 a convex knife edge? */
static int knife(const struct tracer_mesh *m, size_t t1, size_t t2,
		 struct vec3 *n1, struct vec3 *n2)
{
	struct vec3 c1 = tri_centroid(m, t1), c2 = tri_centroid(m, t2);
	double cw = cos(TRACER_EDGE_MAX_WEDGE_DEG * (M_PI / 180.0));

	*n1 = tri_normal(m, t1);
	*n2 = tri_normal(m, t2);
	/* convex: each centroid behind the other face's plane; the wedge
	 * w = pi - angle(n1, n2) < max  <=>  n1.n2 < -cos(max) */
	return v3_dot(*n1, v3_sub(c2, c1)) < -1e-9 &&
	       v3_dot(*n2, v3_sub(c1, c2)) < -1e-9 &&
	       v3_dot(*n1, *n2) < -cw;
}

/* Accumulate edge (a, b) with faces n1, n2 into the tips of a and b; the
 * side labels follow the vertex's first edge (n1 nearer its n1). */
static void add_tip(struct tip *t, struct vec3 e, struct vec3 n1,
		    struct vec3 n2, int group)
{
	if (t->count > 0) {
		if (v3_dot(n1, t->n1) < v3_dot(n2, t->n1)) {
			struct vec3 x = n1;

			n1 = n2;
			n2 = x;
		}
		if (v3_dot(e, t->e) < 0.0)
			e = v3_scale(e, -1.0);
	} else {
		t->group = group;
	}
	t->e = v3_add(t->e, e);
	t->n1 = v3_add(t->n1, n1);
	t->n2 = v3_add(t->n2, n2);
	t->count++;
}

static int edge_group(struct tracer_scene *s, int g, struct stray_error *err)
{
	char name[TRACER_GROUP_NAME_MAX];
	int k;

	snprintf(name, sizeof(name), "%.25s_edge", s->mesh.group_name[g]);
	if (tracer_mesh_find_group(&s->mesh, name) >= 0)
		return tracer_mesh_find_group(&s->mesh, name);
	k = tracer_mesh_group(&s->mesh, name, err);
	if (k >= 0)
		s->material[k] = s->material[g];
	return k;
}

/* The fillet at one tip: cut-back vertices and the arc; 0 or an error. */
static int make_arc(struct tracer_scene *s, uint32_t v, struct tip *t,
		    double r, struct stray_error *err)
{
	struct vec3 p = vert(&s->mesh, v), e = v3_norm(t->e);
	struct vec3 n1 = v3_norm(t->n1), n2 = v3_norm(t->n2), d1, d2, c;
	double w, len;
	int k, rc = STRAY_OK;

	/* normals without their component along the edge */
	n1 = v3_norm(v3_sub(n1, v3_scale(e, v3_dot(n1, e))));
	n2 = v3_norm(v3_sub(n2, v3_scale(e, v3_dot(n2, e))));
	d1 = v3_norm(v3_cross(e, n1));
	if (v3_dot(d1, n2) > 0.0)
		d1 = v3_scale(d1, -1.0);
	d2 = v3_norm(v3_cross(e, n2));
	if (v3_dot(d2, n1) > 0.0)
		d2 = v3_scale(d2, -1.0);
	w = acos(fmax(-1.0, fmin(1.0, v3_dot(d1, d2))));
	len = r / tan(w / 2.0);
	c = v3_sub(v3_add(p, v3_scale(d1, len)), v3_scale(n1, r));
	t->c = c;
	for (k = 0; k <= ARC_SEG && !rc; k++) {
		double phi = acos(fmax(-1.0, fmin(1.0, v3_dot(n1, n2))));
		double f = (double)k / ARC_SEG, sn = sin(phi);
		struct vec3 u = sn > 1e-12 ?
			v3_add(v3_scale(n1, sin((1.0 - f) * phi) / sn),
			       v3_scale(n2, sin(f * phi) / sn)) : n1;
		struct vec3 q = v3_add(c, v3_scale(u, r));
		uint32_t idx;

		rc = tracer_mesh_add_vertex(&s->mesh, q.x, q.y, q.z, &idx,
					    err);
		if (k == 0)
			t->arc = t->v1 = idx;
		if (k == ARC_SEG)
			t->v2 = idx;
	}
	return rc;
}

/* Strip triangles between the arcs of tips a and b, facing out of the
 * fillet. */
static int strip(struct tracer_scene *s, const struct tip *ta,
		 const struct tip *tb, int group, struct stray_error *err)
{
	int rc = STRAY_OK;
	uint32_t k;

	/* the same faces on both sides: b's arc may run the other way */
	int flip = v3_dot(v3_norm(ta->n1), v3_norm(tb->n1)) <
		   v3_dot(v3_norm(ta->n1), v3_norm(tb->n2));

	for (k = 0; k < ARC_SEG && !rc; k++) {
		uint32_t kb = flip ? ARC_SEG - k : k;
		uint32_t kb1 = flip ? ARC_SEG - k - 1 : k + 1;
		uint32_t q[4] = { ta->arc + k, ta->arc + k + 1,
				  tb->arc + kb1, tb->arc + kb };
		struct vec3 p0 = vert(&s->mesh, q[0]), p1 = vert(&s->mesh, q[1]);
		struct vec3 p2 = vert(&s->mesh, q[2]);
		struct vec3 n = v3_cross(v3_sub(p1, p0), v3_sub(p2, p0));
		/* outward: away from the fillet's axis */
		struct vec3 out = v3_sub(v3_scale(v3_add(p0, p2), 0.5),
			v3_scale(v3_add(ta->c, tb->c), 0.5));

		if (v3_dot(n, out) < 0.0) {
			uint32_t x = q[1];

			q[1] = q[3];
			q[3] = x;
		}
		rc = tracer_mesh_add_triangle(&s->mesh, q[0], q[1], q[2],
					      group, err);
		if (!rc)
			rc = tracer_mesh_add_triangle(&s->mesh, q[0], q[2],
						      q[3], group, err);
	}
	return rc;
}

/* Point the tip's triangles at the cut-back vertices (side by normal). */
static void cut_back(struct tracer_mesh *m, const uint32_t *weld_of,
		     const struct tip *tips, size_t n_tri0)
{
	size_t t;
	int k;

	for (t = 0; t < n_tri0; t++) {
		struct vec3 n = tri_normal(m, t);

		for (k = 0; k < 3; k++) {
			uint32_t w = weld_of[m->tri[3 * t + k]];
			const struct tip *tp = &tips[w];
			double s1, s2;

			if (tp->count == 0)
				continue;
			s1 = v3_dot(n, v3_norm(tp->n1));
			s2 = v3_dot(n, v3_norm(tp->n2));
			if (fmax(s1, s2) < 0.5)
				continue;	/* a third face: leave it */
			m->tri[3 * t + k] = s1 >= s2 ? tp->v1 : tp->v2;
		}
	}
}

int tracer_mesh_round_edges(struct tracer_scene *s, double r,
			    struct stray_error *err)
{
	struct tracer_mesh *m = &s->mesh;
	size_t nt = m->n_tri, nv = m->n_vert, i, n_e = 0, n_knife = 0;
	uint32_t *weld_of = NULL;
	struct edge *ed = NULL, *kn = NULL;
	struct tip *tips = NULL;
	int rc = STRAY_OK;

	if (!(r > 0.0) || nt == 0)
		return STRAY_OK;
	weld_of = malloc(nv * sizeof(*weld_of));
	ed = malloc(3 * nt * sizeof(*ed));
	kn = malloc(3 * nt * sizeof(*kn));
	tips = calloc(nv, sizeof(*tips));
	if (!weld_of || !ed || !kn || !tips || weld(m, weld_of)) {
		rc = stray_error_set(err, STRAY_ENOMEM, "edge_radius",
				     "out of memory");
		goto out;
	}
	for (i = 0; i < nt; i++) {
		int k;

		for (k = 0; k < 3; k++) {
			uint32_t a = weld_of[m->tri[3 * i + k]];
			uint32_t b = weld_of[m->tri[3 * i + (k + 1) % 3]];

			if (a == b)
				continue;
			ed[n_e].a = a < b ? a : b;
			ed[n_e].b = a < b ? b : a;
			ed[n_e].tri = (uint32_t)i;
			n_e++;
		}
	}
	qsort(ed, n_e, sizeof(*ed), cmp_edge);
	for (i = 0; i + 1 < n_e; i++) {
		struct vec3 n1, n2, e;

		if (ed[i].a != ed[i + 1].a || ed[i].b != ed[i + 1].b ||
		    (i + 2 < n_e && ed[i + 2].a == ed[i].a &&
		     ed[i + 2].b == ed[i].b) ||
		    (i > 0 && ed[i - 1].a == ed[i].a && ed[i - 1].b == ed[i].b))
			continue;	/* boundary or non-manifold */
		if (!knife(m, ed[i].tri, ed[i + 1].tri, &n1, &n2))
			continue;
		e = v3_norm(v3_sub(vert(m, ed[i].b), vert(m, ed[i].a)));
		add_tip(&tips[ed[i].a], e, n1, n2, m->group[ed[i].tri]);
		add_tip(&tips[ed[i].b], e, n1, n2, m->group[ed[i].tri]);
		kn[n_knife++] = ed[i];
		i++;
	}
	for (i = 0; i < nv && !rc; i++)
		if (tips[i].count > 0)
			rc = make_arc(s, (uint32_t)i, &tips[i], r, err);
	if (!rc)
		cut_back(m, weld_of, tips, nt);
	for (i = 0; i < n_knife && !rc; i++) {
		int g = edge_group(s, tips[kn[i].a].group, err);

		rc = g < 0 ? (err ? err->code : STRAY_EINVAL) :
		     strip(s, &tips[kn[i].a], &tips[kn[i].b], g, err);
	}
out:
	free(weld_of);
	free(ed);
	free(kn);
	free(tips);
	return rc;
}
