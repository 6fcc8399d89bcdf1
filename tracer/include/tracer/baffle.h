/*
 * baffle.h - the parametric axisymmetric vane baffle; `ref4` of
 * ../shared/reference/ref4-baffle.md is its default.  Every number is a
 * parameter, settable by name (`--set key=value`).
 *
 * z runs along the boresight toward the sky; units mm and degrees.  The
 * vanes' apertures sit on a cone from the pupil rim unless a vane's own
 * radius is set.  The bevel (a wedge of bevel_angle_deg) is cut into the
 * lower or the upper face; a knife-edge radius > 0 is a real fillet
 * tangent to the flat face and the bevel, material removed.
 */
#ifndef TRACER_BAFFLE_H
#define TRACER_BAFFLE_H

#include "stray/error.h"
#include "tracer/scene.h"

#define TRACER_VANES_MAX 8

enum tracer_bevel_face { TRACER_BEVEL_LOWER, TRACER_BEVEL_UPPER };

struct tracer_baffle {
	int n_vanes;
	double vane_z[TRACER_VANES_MAX];	/* top face of each vane */
	double vane_r[TRACER_VANES_MAX];	/* aperture; <= 0: on the cone */
	double vane_thickness;
	double bevel_angle_deg;
	enum tracer_bevel_face bevel_face;
	double edge_radius;
	double pupil_radius, pupil_z;	/* detector disk */
	double cone_half_angle_deg;
	double tube_inner_radius, tube_wall;
	double reflectance;		/* interior Lambertian */
	double exterior_reflectance;	/* exterior mirror */
	double beam_margin;		/* beam radius beyond vane 1 aperture */
	double accept_half_angle_deg;	/* detector acceptance; 0 = all */
	int segments;			/* around the axis */
	int arc_segments;		/* along the fillet */
};

/* The ref4 reference baffle. */
void tracer_baffle_ref4(struct tracer_baffle *b);

/* Set one parameter from `key=value` text; errors name key and value. */
int tracer_baffle_set(struct tracer_baffle *b, const char *assignment,
		      struct stray_error *err);

/* Aperture radius of vane i (its innermost design radius). */
double tracer_baffle_aperture(const struct tracer_baffle *b, int i);

/* Check ranges and ordering of the parameters. */
int tracer_baffle_check(const struct tracer_baffle *b,
			struct stray_error *err);

/* Build the mesh, materials, detector and beam of the baffle into s. */
int tracer_baffle_build(const struct tracer_baffle *b,
			struct tracer_scene *s, struct stray_error *err);

/* The parameter names (--set keys of ref4 and "type": "vanes" scenes),
 * one string so `stray trace --help` can print it in its usage text;
 * docs/scene.md gives each key's unit and limits. */
#define TRACER_BAFFLE_KEYS \
	"n_vanes vaneK_z vaneK_r (K = 1..8) vane_thickness\n" \
	"bevel_angle_deg bevel_face=lower|upper edge_radius pupil_radius\n" \
	"pupil_z cone_half_angle_deg tube_inner_radius tube_wall\n" \
	"reflectance exterior_reflectance beam_margin\n" \
	"accept_half_angle_deg segments arc_segments"

#endif /* TRACER_BAFFLE_H */
