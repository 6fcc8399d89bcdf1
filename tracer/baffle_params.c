/*
 * baffle_params.c - the baffle's parameters: ref4 defaults, `key=value`
 * overrides and range checks.
 */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "tracer/baffle.h"

void tracer_baffle_ref4(struct tracer_baffle *b)
{
	int i;

	memset(b, 0, sizeof(*b));
	b->n_vanes = 4;
	for (i = 0; i < 4; i++)
		b->vane_z[i] = -10.0 * i;
	b->vane_thickness = 1.0;
	b->bevel_angle_deg = 45.0;
	b->bevel_face = TRACER_BEVEL_LOWER;
	b->edge_radius = 0.0;
	b->pupil_radius = 6.5;
	b->pupil_z = -40.0;
	b->cone_half_angle_deg = 10.5;
	b->tube_inner_radius = 20.0;
	b->tube_wall = 1.5;
	b->reflectance = 0.04;
	b->exterior_reflectance = 1.0;
	b->beam_margin = 0.1;
	b->accept_half_angle_deg = 0.0;
	b->segments = 256;
	b->arc_segments = 16;
}

double tracer_baffle_aperture(const struct tracer_baffle *b, int i)
{
	double t = tan(b->cone_half_angle_deg * (M_PI / 180.0));

	if (b->vane_r[i] > 0.0)
		return b->vane_r[i];
	return b->pupil_radius + (b->vane_z[i] - b->pupil_z) * t;
}

struct key {
	const char *name;
	size_t offset;
	int is_int;
};

#define KEY_D(f) { #f, offsetof(struct tracer_baffle, f), 0 }
#define KEY_I(f) { #f, offsetof(struct tracer_baffle, f), 1 }

static const struct key keys[] = {
	KEY_I(n_vanes), KEY_D(vane_thickness), KEY_D(bevel_angle_deg),
	KEY_D(edge_radius), KEY_D(pupil_radius), KEY_D(pupil_z),
	KEY_D(cone_half_angle_deg), KEY_D(tube_inner_radius),
	KEY_D(tube_wall), KEY_D(reflectance), KEY_D(exterior_reflectance),
	KEY_D(beam_margin), KEY_D(accept_half_angle_deg), KEY_I(segments),
	KEY_I(arc_segments),
};

/* The address of the field named `name`, including vaneK_z / vaneK_r. */
static void *field_of(struct tracer_baffle *b, const char *name, int *is_int)
{
	size_t i;
	int k;
	char what;

	*is_int = 0;
	for (i = 0; i < sizeof(keys) / sizeof(keys[0]); i++)
		if (strcmp(keys[i].name, name) == 0) {
			*is_int = keys[i].is_int;
			return (char *)b + keys[i].offset;
		}
	if (sscanf(name, "vane%d_%c", &k, &what) == 2 && k >= 1 &&
	    k <= TRACER_VANES_MAX && strlen(name) == (k >= 10 ? 8u : 7u)) {
		if (what == 'z')
			return &b->vane_z[k - 1];
		if (what == 'r')
			return &b->vane_r[k - 1];
	}
	return NULL;
}

int tracer_baffle_set(struct tracer_baffle *b, const char *assignment,
		      struct stray_error *err)
{
	char name[64];
	const char *eq = strchr(assignment, '=');
	char *end;
	double v;
	void *f;
	int is_int;

	if (!eq || eq == assignment || (size_t)(eq - assignment) >= sizeof(name)) {
		stray_error_set(err, STRAY_EINVAL, "--set",
				"expected key=value");
		stray_error_text(err, assignment);
		return STRAY_EINVAL;
	}
	memcpy(name, assignment, (size_t)(eq - assignment));
	name[eq - assignment] = '\0';
	if (strcmp(name, "bevel_face") == 0) {
		if (strcmp(eq + 1, "lower") == 0 || strcmp(eq + 1, "upper") == 0) {
			b->bevel_face = eq[1] == 'l' ? TRACER_BEVEL_LOWER :
						       TRACER_BEVEL_UPPER;
			return STRAY_OK;
		}
		stray_error_set(err, STRAY_EINVAL, "bevel_face",
				"must be lower or upper");
		stray_error_text(err, eq + 1);
		return STRAY_EINVAL;
	}
	f = field_of(b, name, &is_int);
	if (!f) {
		stray_error_set(err, STRAY_ENOTFOUND, "--set",
				"unknown baffle parameter");
		stray_error_text(err, name);
		return STRAY_ENOTFOUND;
	}
	errno = 0;
	v = strtod(eq + 1, &end);
	if (end == eq + 1 || *end || errno || !isfinite(v) ||
	    (is_int && v != floor(v))) {
		stray_error_set(err, STRAY_EINVAL, "--set", is_int ?
				"value is not an integer" :
				"value is not a finite number");
		stray_error_text(err, assignment);
		return STRAY_EINVAL;
	}
	if (is_int)
		*(int *)f = (int)v;
	else
		*(double *)f = v;
	return STRAY_OK;
}

static int bad(struct stray_error *err, const char *field, double v,
	       const char *why)
{
	return stray_error_set_value(err, STRAY_EINVAL, field, why, v);
}

/* The knife-edge fillet must fit on the bevel and the flat face. */
static double max_edge_radius(const struct tracer_baffle *b)
{
	double phi = b->bevel_angle_deg * (M_PI / 180.0);
	double run = b->vane_thickness / tan(phi);
	double bevel_len = b->vane_thickness / sin(phi);

	/* tangent length rho / tan(phi/2) must stay on both faces */
	return 0.99 * fmin(run, bevel_len) * tan(phi / 2.0);
}

int tracer_baffle_check(const struct tracer_baffle *b,
			struct stray_error *err)
{
	int i;

	if (b->n_vanes < 1 || b->n_vanes > TRACER_VANES_MAX)
		return bad(err, "n_vanes", b->n_vanes, "must be 1 to 8");
	if (!(b->vane_thickness > 0.0))
		return bad(err, "vane_thickness", b->vane_thickness,
			   "must be positive");
	if (!(b->bevel_angle_deg > 5.0 && b->bevel_angle_deg <= 90.0))
		return bad(err, "bevel_angle_deg", b->bevel_angle_deg,
			   "must be in (5, 90]");
	if (b->edge_radius < 0.0 || b->edge_radius > max_edge_radius(b))
		return bad(err, "edge_radius", b->edge_radius,
			   "must be >= 0 and fit on the bevel");
	if (!(b->pupil_radius > 0.0))
		return bad(err, "pupil_radius", b->pupil_radius,
			   "must be positive");
	if (!(b->tube_wall > 0.0))
		return bad(err, "tube_wall", b->tube_wall, "must be positive");
	if (b->reflectance < 0.0 || b->reflectance > 1.0)
		return bad(err, "reflectance", b->reflectance,
			   "must be in [0, 1]");
	if (b->exterior_reflectance < 0.0 || b->exterior_reflectance > 1.0)
		return bad(err, "exterior_reflectance", b->exterior_reflectance,
			   "must be in [0, 1]");
	if (b->beam_margin < 0.0)
		return bad(err, "beam_margin", b->beam_margin,
			   "must be >= 0");
	if (b->segments < 8 || b->segments > 4096)
		return bad(err, "segments", b->segments, "must be 8 to 4096");
	if (b->arc_segments < 1 || b->arc_segments > 256)
		return bad(err, "arc_segments", b->arc_segments,
			   "must be 1 to 256");
	for (i = 0; i < b->n_vanes; i++) {
		double r = tracer_baffle_aperture(b, i);
		double bottom = i + 1 < b->n_vanes ? b->vane_z[i + 1] :
						     b->pupil_z;

		if (i > 0 && !(b->vane_z[i] < b->vane_z[i - 1]))
			return bad(err, "vane_z", b->vane_z[i],
				   "vanes must descend from vane 1");
		if (!(b->vane_z[i] - b->vane_thickness > bottom))
			return bad(err, "vane_z", b->vane_z[i],
				   "vane overlaps the next vane or the floor");
		if (!(r > 0.0 && r + b->vane_thickness /
		      tan(b->bevel_angle_deg * M_PI / 180.0) <
		      b->tube_inner_radius))
			return bad(err, "vane_r", r,
				   "aperture must lie inside the tube");
	}
	if (!(b->pupil_radius < b->tube_inner_radius))
		return bad(err, "pupil_radius", b->pupil_radius,
			   "must be smaller than tube_inner_radius");
	return STRAY_OK;
}
