/*
 * angles_auto.c - the default angle grid of a trace, fitted to the scene
 * (issue 23 item 5).
 *
 * A fixed grid (5 deg steps to 30 deg) steps over a narrow baffle's
 * cut-off: the angle beyond which no source ray reaches the detector
 * without a scatter, where alpha falls by orders of magnitude within a
 * fraction of a degree and where the exclusion angle of a narrow baffle
 * lies.  Before the trace, the direct fraction D(theta) - the share of
 * detector points the collimated beam reaches unobstructed through the
 * entrance aperture - is found on a 0.1 deg lattice by shadow rays
 * (deterministic, no Monte Carlo), and the grid is made finest where D
 * ends.
 */
#include <math.h>
#include <stdlib.h>

#include "stray/errfmt.h"
#include "tracer/angles.h"
#include "tracer/scene.h"

#define LATTICE 900	/* 0.1 deg steps over [0, 90] */
/* Detector points: a SIDE x SIDE grid of the unit square, its edges
 * included: they map onto the detector's rim (the concentric disk map,
 * 4 (SIDE - 1) points 360/128 deg apart for SIDE 33), where the last
 * direct ray of a cut-off leaves from. */
#define SIDE 33

/* D(theta_k = k / 10 deg) for k = 0..LATTICE, as lit point counts. */
static void direct_counts(const struct tracer_scene *s, struct vec3 *dirs,
			  unsigned char *occ, int *lit)
{
	int i, j, k;

	for (k = 0; k <= LATTICE; k++) {
		dirs[k] = tracer_source_dir(k / 10.0);
		lit[k] = 0;
	}
	for (i = 0; i < SIDE; i++)
		for (j = 0; j < SIDE; j++) {
			struct vec3 x = tracer_detector_sample_point(&s->det,
				(double)i / (SIDE - 1), (double)j / (SIDE - 1));
			struct vec3 o = tracer_offset_origin(x, s->det.normal);

			tracer_scene_occluded_fan(s, o, dirs, LATTICE + 1, occ);
			for (k = 0; k <= LATTICE; k++)
				lit[k] += !occ[k] &&
					tracer_detector_accepts(&s->det,
								dirs[k]) &&
					tracer_beam_covers(&s->beam, dirs[k], x);
		}
}

int tracer_angles_auto(const struct tracer_scene *s, double **theta_deg,
		       size_t *n, double *cutoff_deg, struct stray_error *err)
{
	struct vec3 *dirs = malloc((LATTICE + 1) * sizeof(*dirs));
	unsigned char *occ = malloc(LATTICE + 1);
	int *lit = malloc((LATTICE + 1) * sizeof(int));
	int k, kc = -1;
	double lo, hi, *t = NULL;
	size_t m = 0;

	if (dirs && occ && lit) {
		direct_counts(s, dirs, occ, lit);
		t = malloc((LATTICE + 1) * sizeof(double));
	}
	free(dirs);
	free(occ);
	if (!t) {
		free(lit);
		return stray_error_set(err, STRAY_ENOMEM, "--angles",
				       "out of memory");
	}
	for (k = 0; k < LATTICE; k++)	/* 90 deg: in the aperture plane */
		if (lit[k] > 0)
			kc = k;
	/* The cut-off lies between the last lit lattice angle and the next;
	 * with nothing lit on axis the trace refuses the scene itself. */
	*cutoff_deg = kc < 0 ? 0.0 : (kc + 1) / 10.0;
	lo = *cutoff_deg - 1.0;
	hi = *cutoff_deg + 1.0;
	/* 1 deg steps where the direct light is smooth, 0.1 deg within a
	 * degree of the cut-off, 0.5 deg beyond it (as the fixed grid did
	 * from 30 deg): a superset of the old default 0:30:5,30:90:0.5 */
	for (k = 0; k <= LATTICE; k++) {
		double a = k / 10.0;

		if (k % 10 == 0 || (a >= lo - 1e-9 && a <= hi + 1e-9) ||
		    (k % 5 == 0 && a > hi))
			t[m++] = a;
	}
	free(lit);
	*theta_deg = t;
	*n = m;
	return STRAY_OK;
}
