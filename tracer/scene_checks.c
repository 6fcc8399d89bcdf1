/*
 * scene_checks.c - what a CAD scene is checked for once loaded (issue 23
 * item 4): its winding made outward (mesh_orient.h) and its units against
 * the detector it surrounds.
 */
#include <math.h>
#include <stdio.h>

#include "stray/errfmt.h"
#include "tracer/mesh_orient.h"
#include "tracer/scene_file.h"

/* The largest extent of the mesh's bounding box, mm. */
static double mesh_extent(const struct tracer_mesh *m)
{
	float lo[3] = { INFINITY, INFINITY, INFINITY };
	float hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	double d = 0.0;
	size_t i;
	int k;

	for (i = 0; i < m->n_vert; i++)
		for (k = 0; k < 3; k++) {
			lo[k] = fminf(lo[k], m->vert[3 * i + k]);
			hi[k] = fmaxf(hi[k], m->vert[3 * i + k]);
		}
	for (k = 0; k < 3 && m->n_vert; k++)
		d = fmax(d, (double)hi[k] - lo[k]);
	return d;
}

/* A baffle surrounds its detector: a mesh smaller than the detector is
 * in other units (metres: 1000 x too small); one 10^4 detector sizes
 * across is too (micrometres). */
static int check_units(const char *path, const struct tracer_scene *s,
		       struct stray_error *err)
{
	double ext = mesh_extent(&s->mesh);
	double det = s->det.shape == TRACER_DET_DISK ? 2.0 * s->det.radius_mm
		: 2.0 * fmax(s->det.half_w_mm, s->det.half_h_mm);

	if (ext >= det && ext <= 1e4 * det)
		return STRAY_OK;
	stray_error_set_value(err, STRAY_EINVAL, "scale_mm",
		ext < det ? "the mesh spans this many mm, less than the "
			    "detector it surrounds: is the file in metres "
			    "(\"scale_mm\": 1000) or inches (25.4)?"
			  : "the mesh spans this many mm, 10^4 detectors "
			    "across: is the file in micrometres "
			    "(\"scale_mm\": 0.001)?", ext);
	stray_error_locate(err, path, 0);
	return STRAY_EINVAL;
}

int tracer_scene_mesh_checks(const char *path, struct tracer_scene *s,
			     struct stray_error *err)
{
	struct tracer_orient_report r;
	int rc = tracer_mesh_orient(&s->mesh, &r, err);

	if (rc) {
		stray_error_locate(err, path, 0);
		return rc;
	}
	if (r.turned_inward || r.turned_inconsistent)
		snprintf(s->note, sizeof(s->note), "winding: %zu triangles "
			 "of %zu closed parts wound inward and %zu that "
			 "disagreed with their part turned outward (%zu parts "
			 "in all)", r.turned_inward, r.inward_parts,
			 r.turned_inconsistent, r.parts);
	return check_units(path, s, err);
}
