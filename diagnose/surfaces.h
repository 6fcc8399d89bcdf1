/*
 * surfaces.h - what the files of the surface at fault share (private to
 * diagnose/): the path table as re-weightable rows (surfaces.c), for the
 * fit (surfaces_fit.c) and the extended model (surfaces_model.c).
 */
#ifndef DIAGNOSE_SURFACES_H
#define DIAGNOSE_SURFACES_H

#include <stddef.h>

#include "diagnose/diag_surfaces.h"
#include "tracer/integrator.h"
#include "tracer/scene.h"

struct diag_surf_table {
	size_t n_theta, n_rows;
	double *theta;		/* traced angles, [0] = 0 */
	unsigned *j;		/* row -> traced angle */
	unsigned char *n_c;	/* row -> visits of candidate groups */
	unsigned char (*c)[TRACER_SEQ_MAX];
	double *v, *var;
	int n_cand;
	int group[DIAG_SURF_MAX], abg[DIAG_SURF_MAX];
	double rho[DIAG_SURF_MAX];
	char name[DIAG_SURF_MAX][32];
};

/* Trace scene (a name and its sets) at theta (0 and the measured angles)
 * through e's runner, with e's lens, paths, seed and threads. */
int diag_surf_trace_scene(struct diag_eval *e, const char *scene,
			  const char *const *sets, int n_sets, int record,
			  double *theta, size_t n_theta,
			  struct tracer_result *r, struct tracer_scene *s,
			  struct stray_error *err);

/* 0 and the measured angles, sorted, unique (malloc'd; NULL: no memory). */
double *diag_surf_angles(const struct diag_eval *e, size_t *n);

/* The traced angle nearest below |th| (th folded into 0..180). */
size_t diag_surf_find_theta(const struct diag_surf_table *t, double th);

#endif /* DIAGNOSE_SURFACES_H */
