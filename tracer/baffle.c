/*
 * baffle.c - the parametric vane baffle as a mesh: its (r, z) profile, a
 * closed clockwise polygon whose left normal points into the air, revolved
 * about the z axis; then the floor, the detector, materials and beam.
 * Each vane part is its own surface group (top, edge, bevel, bottom; wall
 * below it) so the path report can name them (thesis §5.3).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tracer/baffle.h"

#define PROFILE_MAX (8 + TRACER_VANES_MAX * (8 + 260))

struct profile {
	int n;
	int top1;			/* start of vane 1's flat top face */
	double r[PROFILE_MAX], z[PROFILE_MAX];
	int group[PROFILE_MAX];		/* group of the segment i -> i+1 */
};

static void push(struct profile *p, double r, double z, int group)
{
	if (p->n < PROFILE_MAX) {
		p->r[p->n] = r;
		p->z[p->n] = z;
		p->group[p->n] = group;
		p->n++;
	}
}

struct vane_groups {
	int top, edge, bevel, bottom;
};

/*
 * The inner-edge chain of a vane with its bevel on the lower face, from
 * the inner end of the bottom face to the start of the top face: bevel,
 * then the fillet arc (centre on the wedge bisector, tangent to both
 * faces, spanning 180 - phi degrees).
 */
static int lower_chain(const struct tracer_baffle *b, double r0, double zt,
		       double cr[], double cz[])
{
	double phi = b->bevel_angle_deg * (M_PI / 180.0);
	double run = b->vane_thickness / tan(phi);
	double rho = b->edge_radius, len, cx, cy, a_top;
	int n = 0, k;

	cr[n] = r0 + run;
	cz[n++] = zt - b->vane_thickness;
	if (rho <= 0.0) {
		cr[n] = r0;
		cz[n++] = zt;
		return n;
	}
	len = rho / tan(phi / 2.0);	/* tip to each tangent point */
	cx = r0 + len;
	cy = zt - rho;
	a_top = M_PI / 2.0;
	for (k = 0; k <= b->arc_segments; k++) {
		double a = a_top + (M_PI - phi) *
			   (1.0 - (double)k / b->arc_segments);

		cr[n] = cx + rho * cos(a);
		cz[n++] = cy + rho * sin(a);
	}
	cr[n - 1] = cx;		/* exact tangent point on the top face */
	cz[n - 1] = zt;
	return n;
}

static void add_vane(const struct tracer_baffle *b, int i,
		     const struct vane_groups *g, struct profile *p)
{
	double cr[300], cz[300];
	double zt = b->vane_z[i], zb = zt - b->vane_thickness;
	int n = lower_chain(b, tracer_baffle_aperture(b, i), zt, cr, cz);
	int k;

	push(p, b->tube_inner_radius, zb, g->bottom);
	if (b->bevel_face == TRACER_BEVEL_LOWER) {
		for (k = 0; k < n - 1; k++)
			push(p, cr[k], cz[k], k == 0 ? g->bevel : g->edge);
		push(p, cr[n - 1], cz[n - 1], g->top);
		return;
	}
	/* Upper bevel: the same chain mirrored about the mid-plane, reversed. */
	for (k = n - 1; k >= 1; k--)
		push(p, cr[k], zt + zb - cz[k], k == 1 ? g->bevel : g->edge);
	push(p, cr[0], zt + zb - cz[0], g->top);
}

static int make_groups(const struct tracer_baffle *b, struct tracer_mesh *m,
		       struct vane_groups vg[], int wall[],
		       struct stray_error *err)
{
	char name[TRACER_GROUP_NAME_MAX];
	int i;

	for (i = 0; i < b->n_vanes; i++) {
		snprintf(name, sizeof(name), "vane%d_top", i + 1);
		vg[i].top = tracer_mesh_group(m, name, err);
		snprintf(name, sizeof(name), "vane%d_edge", i + 1);
		vg[i].edge = tracer_mesh_group(m, name, err);
		snprintf(name, sizeof(name), "vane%d_bevel", i + 1);
		vg[i].bevel = tracer_mesh_group(m, name, err);
		snprintf(name, sizeof(name), "vane%d_bottom", i + 1);
		vg[i].bottom = tracer_mesh_group(m, name, err);
		snprintf(name, sizeof(name), "wall%d", i + 1);
		wall[i] = tracer_mesh_group(m, name, err);
	}
	return err && err->code ? err->code : STRAY_OK;
}

/* The closed body profile: vane-1 top, rim, outside, then up inside. */
static int body_profile(const struct tracer_baffle *b, struct tracer_mesh *m,
			struct profile *p, struct stray_error *err)
{
	struct vane_groups vg[TRACER_VANES_MAX];
	int wall[TRACER_VANES_MAX], ext, i;
	double r_in = b->tube_inner_radius, r_out = r_in + b->tube_wall;

	if (make_groups(b, m, vg, wall, err))
		return err->code;
	ext = tracer_mesh_group(m, "exterior", err);
	if (ext < 0)
		return err->code;
	p->n = 0;
	/* the polygon is cyclic: the last wall segment closes on vane 1 */
	add_vane(b, 0, &vg[0], p);
	p->top1 = p->n - 1;
	push(p, r_in, b->vane_z[0], ext);	/* top rim */
	push(p, r_out, b->vane_z[0], ext);	/* outer wall */
	push(p, r_out, b->pupil_z, ext);	/* bottom end */
	push(p, r_in, b->pupil_z, wall[b->n_vanes - 1]);
	for (i = b->n_vanes - 1; i >= 1; i--) {
		add_vane(b, i, &vg[i], p);
		push(p, r_in, b->vane_z[i], wall[i - 1]);
	}
	return p->n < PROFILE_MAX ? STRAY_OK :
	       stray_error_set(err, STRAY_EINVAL, "arc_segments",
			       "profile too long");
}

/* A ring of vertices at (r, z); a single vertex on the axis. */
static int add_ring(struct tracer_mesh *m, double r, double z, int nseg,
		    uint32_t *base, struct stray_error *err)
{
	uint32_t idx;
	int j, rc;

	if (r == 0.0)
		return tracer_mesh_add_vertex(m, 0.0, 0.0, z, base, err);
	for (j = 0; j < nseg; j++) {
		double phi = 2.0 * M_PI * j / nseg;

		rc = tracer_mesh_add_vertex(m, r * cos(phi), r * sin(phi), z,
					    &idx, err);
		if (rc)
			return rc;
		if (j == 0)
			*base = idx;
	}
	return STRAY_OK;
}

/*
 * Triangles between ring a (at r0) and ring b (at r1), wound so that the
 * normal is the left normal (-dz, dr) of the profile segment a -> b.
 */
static int revolve(struct tracer_mesh *m, uint32_t a, double r0, uint32_t b,
		   double r1, int nseg, int group, struct stray_error *err)
{
	int j, rc = STRAY_OK;

	for (j = 0; j < nseg && !rc; j++) {
		uint32_t j1 = (uint32_t)((j + 1) % nseg);
		uint32_t A = r0 == 0.0 ? a : a + j, D = r0 == 0.0 ? a : a + j1;
		uint32_t B = r1 == 0.0 ? b : b + j, C = r1 == 0.0 ? b : b + j1;

		if (r1 != 0.0)
			rc = tracer_mesh_add_triangle(m, A, B, C, group, err);
		if (!rc && r0 != 0.0)
			rc = tracer_mesh_add_triangle(m, A, C, D, group, err);
	}
	return rc;
}

static int mesh_body(const struct tracer_baffle *b, struct tracer_mesh *m,
		     const struct profile *p, uint32_t *ring,
		     struct stray_error *err)
{
	int i, rc = STRAY_OK;

	for (i = 0; i < p->n && !rc; i++)
		rc = add_ring(m, p->r[i], p->z[i], b->segments, &ring[i], err);
	for (i = 0; i < p->n && !rc; i++) {
		int k = (i + 1) % p->n;

		if (hypot(p->r[k] - p->r[i], p->z[k] - p->z[i]) < 1e-12)
			continue;
		rc = revolve(m, ring[i], p->r[i], ring[k], p->r[k],
			     b->segments, p->group[i], err);
	}
	return rc;
}

/* Floor annulus and detector disk at the pupil plane, facing +z. */
static int mesh_floor(const struct tracer_baffle *b, struct tracer_mesh *m,
		      const struct profile *p, const uint32_t *ring,
		      struct stray_error *err)
{
	uint32_t wall_foot = 0, rim, centre;
	int floor_g, det_g, i, rc;

	for (i = 0; i < p->n; i++)
		if (p->r[i] == b->tube_inner_radius && p->z[i] == b->pupil_z)
			wall_foot = ring[i];
	floor_g = tracer_mesh_group(m, "floor", err);
	det_g = tracer_mesh_group(m, "detector", err);
	if (floor_g < 0 || det_g < 0)
		return err->code;
	rc = add_ring(m, b->pupil_radius, b->pupil_z, b->segments, &rim, err);
	if (!rc)
		rc = add_ring(m, 0.0, b->pupil_z, b->segments, &centre, err);
	if (!rc)
		rc = revolve(m, rim, b->pupil_radius, wall_foot,
			     b->tube_inner_radius, b->segments, floor_g, err);
	if (!rc)
		rc = revolve(m, centre, 0.0, rim, b->pupil_radius,
			     b->segments, det_g, err);
	return rc;
}

static void set_materials(const struct tracer_baffle *b,
			  struct tracer_scene *s)
{
	size_t g;

	for (g = 0; g < s->mesh.n_group; g++) {
		struct tracer_brdf *mat = &s->material[g];
		const char *name = s->mesh.group_name[g];

		mat->ops = &tracer_brdf_lambert_ops;
		mat->rho = b->reflectance;
		if (strcmp(name, "exterior") == 0) {
			mat->ops = &tracer_brdf_mirror_ops;
			mat->rho = b->exterior_reflectance;
		} else if (strcmp(name, "detector") == 0) {
			mat->ops = NULL;	/* the detector absorbs */
			mat->rho = 0.0;
		}
	}
}

int tracer_baffle_build(const struct tracer_baffle *b,
			struct tracer_scene *s, struct stray_error *err)
{
	struct profile *p;
	uint32_t *ring;
	int rc = tracer_baffle_check(b, err);

	if (rc)
		return rc;
	p = malloc(sizeof(*p));
	ring = malloc(PROFILE_MAX * sizeof(*ring));
	if (!p || !ring) {
		rc = stray_error_set(err, STRAY_ENOMEM, "baffle",
				     "out of memory");
		goto out_free;
	}
	rc = body_profile(b, &s->mesh, p, err);
	if (!rc)
		rc = mesh_body(b, &s->mesh, p, ring, err);
	if (!rc)
		rc = mesh_floor(b, &s->mesh, p, ring, err);
	if (rc)
		goto out_free;
	set_materials(b, s);
	s->det.shape = TRACER_DET_DISK;
	s->det.center = v3(0.0, 0.0, b->pupil_z);
	s->det.normal = v3(0.0, 0.0, 1.0);
	s->det.radius_mm = b->pupil_radius;
	s->det.accept_half_angle_deg = b->accept_half_angle_deg;
	s->beam.center = v3(0.0, 0.0, b->vane_z[0]);
	s->beam.normal = v3(0.0, 0.0, 1.0);
	/* The beam over-fills the entrance as built: out to where vane 1's
	 * flat top face begins (the fillet's tangent point, r0 + rho /
	 * tan(phi/2) with a lower bevel; the bevel's outer end with an upper
	 * one), so every ray into the opening and every lit face below the
	 * top plane is in it, whatever the edge radius. */
	s->beam.radius_mm = p->r[p->top1] + b->beam_margin;
out_free:
	free(p);
	free(ring);
	return rc;
}
