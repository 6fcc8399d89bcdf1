/*
 * mesh.c - growable triangle soup with surface groups.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tracer/mesh.h"

void tracer_mesh_init(struct tracer_mesh *m)
{
	memset(m, 0, sizeof(*m));
}

void tracer_mesh_free(struct tracer_mesh *m)
{
	free(m->vert);
	free(m->tri);
	free(m->group);
	tracer_mesh_init(m);
}

int tracer_mesh_find_group(const struct tracer_mesh *m, const char *name)
{
	size_t i;

	for (i = 0; i < m->n_group; i++)
		if (strcmp(m->group_name[i], name) == 0)
			return (int)i;
	return -1;
}

int tracer_mesh_group(struct tracer_mesh *m, const char *name,
		      struct stray_error *err)
{
	int g = tracer_mesh_find_group(m, name);

	if (g >= 0)
		return g;
	if (m->n_group >= TRACER_GROUP_MAX) {
		stray_error_set_value(err, STRAY_EINVAL, "group",
				      "too many surface groups",
				      TRACER_GROUP_MAX);
		return -1;
	}
	if (strlen(name) >= TRACER_GROUP_NAME_MAX) {
		stray_error_set(err, STRAY_EINVAL, "group",
				"surface group name too long");
		return -1;
	}
	strcpy(m->group_name[m->n_group], name);
	return (int)m->n_group++;
}

static int grow(void **p, size_t *cap, size_t need, size_t elem,
		struct stray_error *err)
{
	size_t n = *cap ? *cap : 256;
	void *q;

	if (need <= *cap)
		return STRAY_OK;
	while (n < need)
		n *= 2;
	q = realloc(*p, n * elem);
	if (!q)
		return stray_error_set(err, STRAY_ENOMEM, "mesh",
				       "out of memory");
	*p = q;
	*cap = n;
	return STRAY_OK;
}

int tracer_mesh_add_vertex(struct tracer_mesh *m, double x, double y,
			   double z, uint32_t *idx, struct stray_error *err)
{
	int rc;

	if (!isfinite(x) || !isfinite(y) || !isfinite(z))
		return stray_error_set(err, STRAY_EINVAL, "vertex",
				       "coordinate is not finite");
	rc = grow((void **)&m->vert, &m->cap_vert, m->n_vert + 1,
		  3 * sizeof(float), err);
	if (rc)
		return rc;
	m->vert[3 * m->n_vert + 0] = (float)x;
	m->vert[3 * m->n_vert + 1] = (float)y;
	m->vert[3 * m->n_vert + 2] = (float)z;
	*idx = (uint32_t)m->n_vert++;
	return STRAY_OK;
}

int tracer_mesh_add_triangle(struct tracer_mesh *m, uint32_t a, uint32_t b,
			     uint32_t c, int group, struct stray_error *err)
{
	size_t cap = m->cap_tri;
	int rc;

	if (a >= m->n_vert || b >= m->n_vert || c >= m->n_vert)
		return stray_error_set(err, STRAY_EINVAL, "face",
				       "vertex index out of range");
	if (group < 0 || (size_t)group >= m->n_group)
		return stray_error_set(err, STRAY_EINVAL, "face",
				       "unknown surface group");
	rc = grow((void **)&m->tri, &m->cap_tri, m->n_tri + 1,
		  3 * sizeof(uint32_t), err);
	if (rc)
		return rc;
	m->cap_tri = cap;	/* the group array grows in step */
	rc = grow((void **)&m->group, &m->cap_tri, m->n_tri + 1,
		  sizeof(uint8_t), err);
	if (rc)
		return rc;
	m->tri[3 * m->n_tri + 0] = a;
	m->tri[3 * m->n_tri + 1] = b;
	m->tri[3 * m->n_tri + 2] = c;
	m->group[m->n_tri++] = (uint8_t)group;
	return STRAY_OK;
}

double tracer_mesh_group_area(const struct tracer_mesh *m, int group)
{
	double area = 0.0;
	size_t i;

	for (i = 0; i < m->n_tri; i++) {
		const float *p0, *p1, *p2;
		double e1[3], e2[3], c[3];
		int k;

		if (m->group[i] != group)
			continue;
		p0 = m->vert + 3 * m->tri[3 * i];
		p1 = m->vert + 3 * m->tri[3 * i + 1];
		p2 = m->vert + 3 * m->tri[3 * i + 2];
		for (k = 0; k < 3; k++) {
			e1[k] = (double)p1[k] - p0[k];
			e2[k] = (double)p2[k] - p0[k];
		}
		c[0] = e1[1] * e2[2] - e1[2] * e2[1];
		c[1] = e1[2] * e2[0] - e1[0] * e2[2];
		c[2] = e1[0] * e2[1] - e1[1] * e2[0];
		area += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
	}
	return area;
}
