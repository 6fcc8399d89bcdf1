/*
 * data.c - the measured curve: an attenuation-curve CSV with a sigma
 * column (docs/formats.md), every row usable in log space.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "diagnose/diag_data.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"

const char *const diag_region_name[DIAG_REGIONS] = {
	"source in field", "transition", "scatter only"
};

#define DIAG_ANGLES_MAX 2000	/* input limit, docs/limits.md */

int diag_data_load(const char *path, struct diag_data *d,
		   struct stray_error *err)
{
	struct stray_curve c;
	size_t i;
	int rc = stray_curve_load(path, &c, err);

	memset(d, 0, sizeof(*d));
	if (rc)
		return rc;
	if (!c.sigma) {
		rc = stray_error_set(err, STRAY_EINVAL, "sigma",
			"the measured curve needs a sigma column (one standard error)");
		stray_error_locate(err, path, 0);
	}
	if (!rc && (c.n < 3 || c.n > DIAG_ANGLES_MAX)) {
		/* every angle is traced once per fitted cause: bounded */
		rc = stray_error_set_value(err, STRAY_EINVAL, "theta_deg",
			c.n < 3 ? "at least 3 measured angles are needed"
				: "at most 2000 measured angles (docs/limits.md)",
			(double)c.n);
		stray_error_locate(err, path, 0);
	}
	for (i = 0; !rc && i < c.n; i++) {
		const char *bad = NULL;
		double v = 0.0;

		if (!(c.alpha[i] > 0.0))
			bad = "alpha", v = c.alpha[i];
		else if (!(c.sigma[i] > 0.0))
			bad = "sigma", v = c.sigma[i];
		else if (!(c.theta_deg[i] >= 0.0 && c.theta_deg[i] < 90.0))
			bad = "theta_deg", v = c.theta_deg[i];
		if (bad) {
			rc = stray_error_set_value(err, STRAY_EINVAL, bad,
				"must be > 0 (alpha, sigma) and theta in [0, 90) "
				"for a log-space fit", v);
			stray_error_locate(err, path, 0);
		}
	}
	if (!rc) {
		d->n = c.n;
		d->theta_deg = malloc(c.n * sizeof(double));
		d->alpha = malloc(c.n * sizeof(double));
		d->sigma = malloc(c.n * sizeof(double));
		d->region = calloc(c.n, sizeof(int));
		if (!d->theta_deg || !d->alpha || !d->sigma || !d->region)
			rc = stray_error_set(err, STRAY_ENOMEM, "diagnose",
					     "out of memory");
	}
	if (!rc) {
		memcpy(d->theta_deg, c.theta_deg, c.n * sizeof(double));
		memcpy(d->alpha, c.alpha, c.n * sizeof(double));
		memcpy(d->sigma, c.sigma, c.n * sizeof(double));
	}
	stray_curve_free(&c);
	if (rc)
		diag_data_free(d);
	return rc;
}

void diag_data_free(struct diag_data *d)
{
	free(d->theta_deg);
	free(d->alpha);
	free(d->sigma);
	free(d->region);
	memset(d, 0, sizeof(*d));
}
