/*
 * diag_data.h - the measured attenuation curve a diagnosis starts from,
 * and the angle regions its residuals are summarised by.
 */
#ifndef DIAGNOSE_DIAG_DATA_H
#define DIAGNOSE_DIAG_DATA_H

#include <stddef.h>

#include "stray/error.h"

struct diag_data {
	size_t n;
	double *theta_deg, *alpha, *sigma;
	int *region;		/* enum diag_region */
	/* the curve's own theta = 0 normalisation row (alpha 1, as `stray
	 * trace` writes it, sigma 0) was given: kept out of the fit (the
	 * model is 1 there by construction), the curve is normalised */
	int normalised;
};

enum diag_region { DIAG_IN_FIELD, DIAG_TRANSITION, DIAG_SCATTER,
		   DIAG_REGIONS };
extern const char *const diag_region_name[DIAG_REGIONS];

/* Load a measured curve (sigma column required); drops nothing silently
 * but the theta = 0 normalisation row (alpha 1, sigma 0: d->normalised):
 * a non-positive alpha or sigma elsewhere is an error naming its line. */
int diag_data_load(const char *path, struct diag_data *d,
		   struct stray_error *err);
void diag_data_free(struct diag_data *d);

#endif /* DIAGNOSE_DIAG_DATA_H */
