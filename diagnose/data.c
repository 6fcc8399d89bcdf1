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
#include "stray/table.h"

const char *const diag_region_name[DIAG_REGIONS] = {
	"source in field", "transition", "scatter only"
};

#define DIAG_ANGLES_MAX 2000	/* input limit, docs/limits.md */

/* The file line of data row i (the curve keeps none), or 0. */
static long row_line(const char *path, size_t i)
{
	struct stray_table t;
	struct stray_error e;
	long line = 0;

	stray_error_clear(&e);
	if (stray_table_read(path, &t, &e) == STRAY_OK && i < t.n_rows)
		line = t.line[i];
	stray_table_free(&t);
	return line;
}

/* The row `stray trace` writes at theta 0: exactly 1 by normalisation. */
static int normalisation_row(const struct stray_curve *c, size_t i)
{
	return c->theta_deg[i] == 0.0 && c->sigma[i] == 0.0 &&
	       fabs(c->alpha[i] - 1.0) <= 1e-9;
}

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

		if (normalisation_row(&c, i)) {
			d->normalised = 1;
			continue;
		}
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
			stray_error_locate(err, path, row_line(path, i));
		}
	}
	if (!rc && c.n - (size_t)d->normalised < 3) {
		rc = stray_error_set_value(err, STRAY_EINVAL, "theta_deg",
			"at least 3 measured angles are needed besides the "
			"theta 0 normalisation row", (double)c.n);
		stray_error_locate(err, path, 0);
	}
	if (!rc) {
		d->theta_deg = malloc(c.n * sizeof(double));
		d->alpha = malloc(c.n * sizeof(double));
		d->sigma = malloc(c.n * sizeof(double));
		d->region = calloc(c.n, sizeof(int));
		if (!d->theta_deg || !d->alpha || !d->sigma || !d->region)
			rc = stray_error_set(err, STRAY_ENOMEM, "diagnose",
					     "out of memory");
	}
	for (i = 0; !rc && i < c.n; i++) {
		if (normalisation_row(&c, i))
			continue;
		d->theta_deg[d->n] = c.theta_deg[i];
		d->alpha[d->n] = c.alpha[i];
		d->sigma[d->n++] = c.sigma[i];
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
