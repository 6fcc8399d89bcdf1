/*
 * lens.h - system curves: the light arriving at the lens per incidence
 * bin beyond its field, for the lens causes (private to diagnose/;
 * diagnose/lens.c).
 */
#ifndef DIAGNOSE_LENS_H
#define DIAGNOSE_LENS_H

#include "diagnose/diag_eval.h"

#define DIAG_LENS_BIN_DEG 1.0
#define DIAG_LENS_BIN_TOP 40.0	/* one bin from here to 180 deg */

/* With e->lens: the bin traces; alpha_nominal the nominal model at the
 * measured angles. */
int diag_lens_prepare(struct diag_eval *e, const double *alpha_nominal,
		      struct stray_error *err);
void diag_lens_bin_edges(const struct diag_eval *e, int b, double *lo,
			 double *hi);
/* The state's lens causes applied to alpha a at measured angle i. */
double diag_lens_apply(const struct diag_eval *e, const struct diag_state *s,
		       size_t i, double a);
void diag_lens_free(struct diag_eval *e);

#endif /* DIAGNOSE_LENS_H */
