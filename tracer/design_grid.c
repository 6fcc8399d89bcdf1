/*
 * design_grid.c - parse grid axes and enumerate their designs.
 */
#include <stdio.h>
#include <string.h>

#include "tracer/design_grid.h"
#include "stray/errfmt.h"

static int bad(struct stray_error *err, const char *text, const char *why)
{
	stray_error_set(err, STRAY_EINVAL, "--grid", why);
	stray_error_text(err, text);
	return STRAY_EINVAL;
}

int design_grid_add(struct design_grid *g, const char *text,
		    struct stray_error *err)
{
	const char *eq = strchr(text, '='), *p;
	struct grid_axis *a;
	size_t klen;
	int i;

	if (g->n_axes >= GRID_AXES_MAX)
		return bad(err, text, "at most 8 axes");
	if (!eq || eq == text || eq[1] == '\0')
		return bad(err, text, "expected key=v1,v2,...");
	klen = (size_t)(eq - text);
	if (klen >= GRID_TEXT_MAX)
		return bad(err, text, "key too long");
	a = &g->axis[g->n_axes];
	memset(a, 0, sizeof(*a));
	memcpy(a->key, text, klen);
	for (i = 0; i < g->n_axes; i++)		/* would repeat every design */
		if (strcmp(g->axis[i].key, a->key) == 0)
			return bad(err, text, "key given twice (one --grid per key)");
	for (p = eq + 1; ; ) {
		const char *c = strchr(p, ',');
		size_t len = c ? (size_t)(c - p) : strlen(p);

		if (len == 0 || len >= GRID_TEXT_MAX)
			return bad(err, text, "empty or too long value");
		if (a->n >= GRID_VALUES_MAX)
			return bad(err, text, "at most 32 values per axis");
		memcpy(a->value[a->n], p, len);
		for (i = 0; i < a->n; i++)
			if (strcmp(a->value[i], a->value[a->n]) == 0)
				return bad(err, text, "value given twice");
		a->n++;
		if (!c)
			break;
		p = c + 1;
	}
	g->n_axes++;
	g->n_designs = 1;
	for (klen = 0; klen < (size_t)g->n_axes; klen++)
		g->n_designs *= (size_t)g->axis[klen].n;
	return STRAY_OK;
}

/* Index of axis k's value in design d (last axis fastest). */
static int value_index(const struct design_grid *g, size_t d, int k)
{
	int i;

	for (i = g->n_axes - 1; i > k; i--)
		d /= (size_t)g->axis[i].n;
	return (int)(d % (size_t)g->axis[k].n);
}

void design_grid_sets(const struct design_grid *g, size_t d,
		      char set[][2 * GRID_TEXT_MAX])
{
	int k;

	for (k = 0; k < g->n_axes; k++)
		snprintf(set[k], 2 * GRID_TEXT_MAX, "%s=%s", g->axis[k].key,
			 g->axis[k].value[value_index(g, d, k)]);
}

void design_grid_label(const struct design_grid *g, size_t d, char *buf,
		       size_t size)
{
	char set[GRID_AXES_MAX][2 * GRID_TEXT_MAX];
	size_t used = 0;
	int k;

	design_grid_sets(g, d, set);
	buf[0] = '\0';
	for (k = 0; k < g->n_axes && used < size; k++)
		used += (size_t)snprintf(buf + used, size - used, "%s%s",
					 k ? " " : "", set[k]);
}
