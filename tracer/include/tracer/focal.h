/*
 * focal.h - the focal-plane stray-light map (issue 13 item 2).
 *
 * The tracer's detector is the lens's entrance pupil.  An ideal lens of
 * focal length f images light arriving at the pupil from direction w
 * (pointing away from the pupil, toward where the light came from) at
 * (x, y) = f (w.s / w.n, w.t / w.n) in the pupil frame (frame_from_normal
 * of the pupil normal n), whatever the pupil point: the path's direction
 * of arrival, not its start point, picks the pixel.  The integrator sums
 * each contribution (the same number alpha sums) into the cell of its
 * image point, or into one "outside" slot when the image point misses the
 * detector; tracer_focal_finish spreads that slot over the detector
 * (the lens's measured region map, or uniformly) and normalises the cells
 * to the per-pixel irradiance ratio E_px / E_src with P(0) = E_src A_cs,
 * whose mean is k_px alpha(theta) (tracer/README.md).
 */
#ifndef TRACER_FOCAL_H
#define TRACER_FOCAL_H

#include <stdbool.h>
#include <stddef.h>

#include "stray/error.h"
#include "tracer/vec.h"

struct tracer_focal {
	double f_mm;			/* ideal lens focal length */
	double half_w_mm, half_h_mm;	/* detector half sizes along s, t */
	int nx, ny;			/* cells along s (cols), t (rows) */
	size_t theta_index;		/* the sweep angle mapped */
};

/* Cells plus the outside slot: the length of the integrator's sums. */
size_t tracer_focal_slots(const struct tracer_focal *fp);

/* Check the fields; errors name the field and value. */
int tracer_focal_check(const struct tracer_focal *fp,
		       struct stray_error *err);

/*
 * Image point (mm, pupil frame f) of light arriving from direction w;
 * false when w does not come from the pupil's front side.
 */
bool tracer_focal_point(const struct tracer_focal *fp, const struct frame *f,
			struct vec3 w, double *x_mm, double *y_mm);

/* Cell (row * nx + col) of light from direction w, or nx * ny (outside). */
size_t tracer_focal_cell(const struct tracer_focal *fp, const struct frame *f,
			 struct vec3 w);

/*
 * How out-of-field light spreads: n regions of the lens's region map
 * (stray reduce --map: fraction of the pixels, level over the mean), or
 * n = 0 for uniform.  The brightest regions go to the cells nearest the
 * image point (src_x_mm, src_y_mm) of the source direction.
 */
struct tracer_focal_spread {
	size_t n;
	const double *fraction, *rel_alpha;
	double src_x_mm, src_y_mm;
};

/*
 * The map from the integrator's cells (tracer_result.focal: P_c / (E A_det),
 * slots as above) and p0 = P(0) / (E A_det) of the same trace
 * (tracer_result_power at theta = 0):
 * map[c] = (P_c / P(0)) A_cs / A_cell, P_c counting the cell's share of the
 * spread outside slot.  The mean of map is (P(theta)/P(0)) A_cs / A_det =
 * k_px alpha exactly.  *in_field: the share of P(theta) imaged in the
 * field.  STRAY_EINVAL when p0 is not positive, STRAY_ENOMEM.
 */
int tracer_focal_finish(const struct tracer_focal *fp, const double *sums,
			double p0, double a_cs_mm2,
			const struct tracer_focal_spread *sp, double *map,
			double *in_field, struct stray_error *err);

#endif /* TRACER_FOCAL_H */
