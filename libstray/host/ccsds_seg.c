/*
 * ccsds_seg.c - the segments of an OEM or AEM as the standard means them:
 * each covers its useable span, a later segment wins where spans overlap
 * (re-issued data replaces the old inside its useable span, as Orekit
 * reads it), and time no segment covers is a hole interpolation never
 * crosses (an 18-day gap between two segments is not flown across).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/ccsds.h"

struct stray_ccsds_seg *stray_ccsds_cover_add(struct stray_ccsds_cover *c)
{
	if (c->n_seg == c->cap_seg) {
		size_t cap = c->cap_seg ? 2 * c->cap_seg : 4;
		struct stray_ccsds_seg *s = realloc(c->seg, cap * sizeof(*s));

		if (!s)
			return NULL;
		c->seg = s;
		c->cap_seg = cap;
	}
	memset(&c->seg[c->n_seg], 0, sizeof(c->seg[0]));
	return &c->seg[c->n_seg++];
}

/* Intervals [a, b] kept sorted and merged: the span later segments own. */
struct span { double a, b; };

static int add_piece(struct stray_ccsds_cover *c, size_t *cap, double a,
		     double b, size_t seg)
{
	if (c->n_piece == *cap) {
		size_t n = *cap ? 2 * *cap : 8;
		struct stray_ccsds_piece *p = realloc(c->piece, n * sizeof(*p));

		if (!p)
			return -1;
		c->piece = p;
		*cap = n;
	}
	c->piece[c->n_piece].a = a;
	c->piece[c->n_piece].b = b;
	c->piece[c->n_piece].seg = seg;
	c->n_piece++;
	return 0;
}

static int by_start(const void *x, const void *y)
{
	const struct stray_ccsds_piece *p = x, *q = y;

	if (p->a != q->a)
		return (p->a > q->a) - (p->a < q->a);
	return (p->seg > q->seg) - (p->seg < q->seg);
}

/* Segment `seg`'s span [a, b] less the union u[0..*n): the pieces it
 * owns; then [a, b] joins the union. */
static int own(struct stray_ccsds_cover *c, size_t *cap, struct span *u,
	       size_t *n, double a, double b, size_t seg)
{
	double at = a;
	size_t i, j, k;
	int advanced = 0;

	for (i = 0; i < *n && at <= b; i++) {
		if (u[i].b < at)
			continue;
		if (u[i].a > b)
			break;
		/* the later segment wins on a shared end: open there */
		if (u[i].a > at && add_piece(c, cap, at, u[i].a, seg) != 0)
			return -1;
		at = u[i].b;
		advanced = 1;
		if (at >= b)
			break;
	}
	/* what is left after the last later span, or a one-epoch segment
	 * that no later one covers */
	if ((at < b || (!advanced && a == b)) &&
	    add_piece(c, cap, at, b, seg) != 0)
		return -1;
	/* merge [a, b] into u (sorted by a) */
	for (j = 0; j < *n && u[j].b < a; j++)
		;
	for (k = j; k < *n && u[k].a <= b; k++) {
		if (u[k].a < a)
			a = u[k].a;
		if (u[k].b > b)
			b = u[k].b;
	}
	memmove(&u[j + 1], &u[k], (*n - k) * sizeof(*u));
	*n = *n - (k - j) + 1;
	u[j].a = a;
	u[j].b = b;
	return 0;
}

int stray_ccsds_cover_build(struct stray_ccsds_cover *c, const double *t,
			    size_t nodes, size_t *bad)
{
	struct span *u;
	size_t i, n_u = 0, cap = 0;
	int rc = 0;

	for (i = 0; i < c->n_seg; i++) {
		struct stray_ccsds_seg *s = &c->seg[i];
		double first = t[s->lo], last = t[s->lo + s->n - 1];

		if (s->n == 0) {
			*bad = i;
			return -1;
		}
		if (!s->have_u0)
			s->u0 = first;
		if (!s->have_u1)
			s->u1 = last;
		if (s->u0 < first || s->u1 > last || s->u0 > s->u1) {
			*bad = i;
			return -1;
		}
		s->gap_s = stray_ccsds_gap_s(t + s->lo, s->n,
					     s->nodes ? s->nodes : nodes);
		if (s->gap_s < 0.0)
			return -2;
	}
	u = malloc((c->n_seg + 1) * sizeof(*u));
	if (!u)
		return -2;
	free(c->piece);
	c->piece = NULL;
	c->n_piece = 0;
	for (i = c->n_seg; i-- > 0 && rc == 0;)
		if (own(c, &cap, u, &n_u, c->seg[i].u0, c->seg[i].u1, i) != 0)
			rc = -2;
	free(u);
	if (rc != 0)
		return rc;
	qsort(c->piece, c->n_piece, sizeof(*c->piece), by_start);
	c->t0 = c->piece[0].a;
	c->t1 = c->piece[0].b;
	for (i = 1; i < c->n_piece; i++)
		if (c->piece[i].b > c->t1)
			c->t1 = c->piece[i].b;
	return 0;
}

long stray_ccsds_cover_find(const struct stray_ccsds_cover *c, double at)
{
	size_t lo = 0, hi = c->n_piece;

	if (c->n_piece == 0 || !(at >= c->piece[0].a))
		return -1;
	/* the last piece starting at or before `at` */
	while (hi - lo > 1) {
		size_t mid = lo + (hi - lo) / 2;

		if (c->piece[mid].a <= at)
			lo = mid;
		else
			hi = mid;
	}
	return at <= c->piece[lo].b ? (long)c->piece[lo].seg : -1;
}

size_t stray_ccsds_cover_holes(const struct stray_ccsds_cover *c,
			       const double *t)
{
	size_t i, j, k = 0;

	for (i = 0; i < c->n_piece; i++) {
		const struct stray_ccsds_piece *p = &c->piece[i];
		const struct stray_ccsds_seg *s = &c->seg[p->seg];

		if (i > 0 && p->a > c->piece[i - 1].b)
			k++;
		for (j = s->lo; j + 1 < s->lo + s->n; j++)
			if (t[j + 1] - t[j] > s->gap_s && t[j + 1] > p->a &&
			    t[j] < p->b)
				k++;
	}
	return k;
}

void stray_ccsds_cover_free(struct stray_ccsds_cover *c)
{
	free(c->seg);
	free(c->piece);
	memset(c, 0, sizeof(*c));
}

int stray_ccsds_cover_finish(struct stray_ccsds_cover *c, const double *t,
			     size_t nodes, const char *file,
			     struct stray_error *err)
{
	size_t bad = 0;
	int rc = stray_ccsds_cover_build(c, t, nodes, &bad);
	char at[48];

	if (rc == -2)
		return stray_error_set(err, STRAY_ENOMEM, "records", NULL);
	if (rc == 0)
		return STRAY_OK;
	snprintf(at, sizeof(at), "segment of META_START at line %ld",
		 c->seg[bad].line);
	return stray_kvn_fail(err, file, c->seg[bad].line,
			      c->seg[bad].n ? "USEABLE_START_TIME" : "data",
			      c->seg[bad].n ? "useable span outside the "
			      "segment's records, or empty"
			      : "a segment without records", at);
}
