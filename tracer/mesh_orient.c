/*
 * mesh_orient.c - make a mesh's winding consistent and outward
 * (mesh_orient.h).  No recursion: the parts are walked with an explicit
 * queue.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "tracer/mesh_orient.h"

struct edge {
	uint32_t lo, hi;	/* welded vertex ids, lo < hi */
	uint32_t slot;		/* 3 * triangle + corner */
	int8_t dir;		/* +1: the triangle runs lo -> hi */
};

static const float *sort_vert;	/* qsort has no context argument */

static int cmp_vert(const void *a, const void *b)
{
	const float *p = sort_vert + 3 * *(const uint32_t *)a;
	const float *q = sort_vert + 3 * *(const uint32_t *)b;
	int k;

	for (k = 0; k < 3; k++)
		if (p[k] != q[k])
			return p[k] < q[k] ? -1 : 1;
	return 0;
}

static int cmp_edge(const void *a, const void *b)
{
	const struct edge *e = a, *f = b;

	if (e->lo != f->lo)
		return e->lo < f->lo ? -1 : 1;
	if (e->hi != f->hi)
		return e->hi < f->hi ? -1 : 1;
	return e->slot < f->slot ? -1 : e->slot > f->slot;
}

/* weld[v]: the smallest index of a vertex at v's position (exporters
 * split shared edges across groups; the positions stay equal). */
static void weld_vertices(const struct tracer_mesh *m, uint32_t *order,
			  uint32_t *weld)
{
	size_t i, j;

	for (i = 0; i < m->n_vert; i++)
		order[i] = (uint32_t)i;
	sort_vert = m->vert;
	qsort(order, m->n_vert, sizeof(*order), cmp_vert);
	for (i = 0; i < m->n_vert; i = j) {
		for (j = i + 1; j < m->n_vert &&
		     cmp_vert(&order[i], &order[j]) == 0; j++)
			;
		while (i < j)
			weld[order[i++]] = order[j - 1];
	}
}

/* Each triangle's neighbour across each corner's edge (-1: none) and
 * whether it runs that edge the same way (then one of them is turned). */
static void link_edges(const struct tracer_mesh *m, const uint32_t *weld,
		       struct edge *e, int64_t *nb, uint8_t *same,
		       struct tracer_orient_report *r)
{
	size_t n = 0, i, j, t;
	int k;

	for (t = 0; t < m->n_tri; t++)
		for (k = 0; k < 3; k++) {
			uint32_t a = weld[m->tri[3 * t + k]];
			uint32_t b = weld[m->tri[3 * t + (k + 1) % 3]];

			nb[3 * t + k] = -2;	/* a degenerate corner */
			if (a == b)
				continue;
			e[n].lo = a < b ? a : b;
			e[n].hi = a < b ? b : a;
			e[n].slot = (uint32_t)(3 * t + k);
			e[n++].dir = a < b ? 1 : -1;
		}
	qsort(e, n, sizeof(*e), cmp_edge);
	for (i = 0; i < n; i = j) {
		for (j = i + 1; j < n && e[j].lo == e[i].lo &&
		     e[j].hi == e[i].hi; j++)
			;
		if (j - i != 2) {
			/* open (-1), or three or more (-3: parts touching
			 * along an edge, which still closes each of them;
			 * no link across it) */
			size_t x;

			for (x = i; x < j; x++)
				nb[e[x].slot] = j - i == 1 ? -1 : -3;
			if (j - i == 1)
				r->open_edges++;
			else
				r->nonmanifold_edges++;
		} else {
			nb[e[i].slot] = e[i + 1].slot / 3;
			nb[e[i + 1].slot] = e[i].slot / 3;
			same[e[i].slot] = same[e[i + 1].slot] =
				e[i].dir == e[i + 1].dir;
		}
	}
}

/* Six times the signed volume a triangle spans with the point o. */
static double volume6(const struct tracer_mesh *m, size_t t, int turned,
		      const double *o)
{
	double p[3][3];
	int c, k;

	for (c = 0; c < 3; c++) {
		uint32_t v = m->tri[3 * t + (turned && c ? 3 - c : c)];

		for (k = 0; k < 3; k++)
			p[c][k] = m->vert[3 * v + k] - o[k];
	}
	return p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
	       p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
	       p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
}

/* One part from triangle seed: turn[] set consistently by a breadth-
 * first walk (queue q), then the minority turned, then, when closed and
 * inward, all of it.  Returns the conflicts (edges that cannot agree). */
static size_t orient_part(const struct tracer_mesh *m, size_t seed,
			  const int64_t *nb, const uint8_t *same,
			  int8_t *turn, uint32_t *q,
			  struct tracer_orient_report *r)
{
	size_t head = 0, tail = 0, i, turned = 0, conflicts = 0;
	int closed = 1, k;
	double o[3] = { 0, 0, 0 }, vol = 0.0;

	turn[seed] = 0;
	q[tail++] = (uint32_t)seed;
	while (head < tail) {
		size_t t = q[head++];

		for (k = 0; k < 3; k++) {
			int64_t u = nb[3 * t + k];
			int8_t want;

			if (u < 0) {
				closed &= u != -1;	/* -1: an open edge */
				continue;
			}
			want = (int8_t)(turn[t] ^ same[3 * t + k]);
			if (turn[u] < 0) {
				turn[u] = want;
				q[tail++] = (uint32_t)u;
			} else if (turn[u] != want) {
				conflicts++;
			}
		}
	}
	for (i = 0; i < tail; i++)
		turned += (size_t)turn[q[i]];
	if (2 * turned > tail) {	/* the seed was in the minority */
		for (i = 0; i < tail; i++)
			turn[q[i]] ^= 1;
		turned = tail - turned;
	}
	r->parts++;
	r->turned_inconsistent += turned;
	if (!closed)
		return conflicts;
	r->closed_parts++;
	for (k = 0; k < 3; k++)	/* about the part's first vertex: small */
		o[k] = m->vert[3 * m->tri[3 * seed] + k];
	for (i = 0; i < tail; i++)
		vol += volume6(m, q[i], turn[q[i]], o);
	if (vol < 0.0) {
		for (i = 0; i < tail; i++)
			turn[q[i]] ^= 1;
		/* the majority was inward and is turned now; the minority
		 * that disagreed with it was right and stays */
		r->inward_parts++;
		r->turned_inward += tail - turned;
		r->turned_inconsistent -= turned;
	}
	return conflicts;
}

int tracer_mesh_orient(struct tracer_mesh *m, struct tracer_orient_report *r,
		       struct stray_error *err)
{
	uint32_t *order = malloc((m->n_vert + 1) * sizeof(*order));
	uint32_t *weld = malloc((m->n_vert + 1) * sizeof(*weld));
	struct edge *e = malloc((3 * m->n_tri + 1) * sizeof(*e));
	int64_t *nb = malloc((3 * m->n_tri + 1) * sizeof(*nb));
	uint8_t *same = calloc(3 * m->n_tri + 1, 1);
	int8_t *turn = malloc(m->n_tri + 1);
	uint32_t *q = malloc((m->n_tri + 1) * sizeof(*q));
	size_t t, conflicts = 0;
	int rc = STRAY_OK;

	memset(r, 0, sizeof(*r));
	if (!order || !weld || !e || !nb || !same || !turn || !q) {
		rc = stray_error_set(err, STRAY_ENOMEM, "mesh", "out of memory");
		goto out;
	}
	weld_vertices(m, order, weld);
	link_edges(m, weld, e, nb, same, r);
	memset(turn, -1, m->n_tri);
	for (t = 0; t < m->n_tri; t++)
		if (turn[t] < 0)
			conflicts += orient_part(m, t, nb, same, turn, q, r);
	if (conflicts) {
		rc = stray_error_set_value(err, STRAY_EINVAL, "mesh",
			"cannot be oriented: edges whose two triangles cannot "
			"agree on a side (a Moebius-like part)",
			(double)(conflicts / 2));
		goto out;
	}
	for (t = 0; t < m->n_tri; t++)
		if (turn[t]) {
			uint32_t v = m->tri[3 * t + 1];

			m->tri[3 * t + 1] = m->tri[3 * t + 2];
			m->tri[3 * t + 2] = v;
		}
out:
	free(order);
	free(weld);
	free(e);
	free(nb);
	free(same);
	free(turn);
	free(q);
	return rc;
}
