/*
 * curve_thin.c - a long curve brought to the flight table's rows
 * (table_build.h, fdrfw_curve_thin).
 *
 * The flight table holds at most FDRFW_CURVE_MAX samples, and the module
 * interpolates log10 alpha linearly between them; the default trace grid
 * (tracer/angles_auto.c) gives 160-190 angles.  The samples are chosen by
 * greedy insertion: from the two ends, the sample the kept ones
 * interpolate worst (in log10 alpha, the floor standing for 0, as the
 * table stores it) is kept next, until the rows are full; what is left
 * out is said as the largest error it leaves.
 */
#include <math.h>
#include <stdlib.h>

#include "fdrfw/table_build.h"
#include "stray/errfmt.h"

static double lg(double a)
{
	return a > 0.0 ? fmax(log10(a), (double)FDRFW_LOG10_ALPHA_FLOOR)
		       : (double)FDRFW_LOG10_ALPHA_FLOOR;
}

/* |log10 alpha_i - the line between kept samples lo and hi| */
static double gap(const struct stray_curve_view *c, size_t lo, size_t hi,
		  size_t i)
{
	double f = (c->theta_deg[i] - c->theta_deg[lo]) /
		   (c->theta_deg[hi] - c->theta_deg[lo]);

	return fabs(lg(c->alpha[i]) - (lg(c->alpha[lo]) +
		    f * (lg(c->alpha[hi]) - lg(c->alpha[lo]))));
}

/* The worst left-out sample (and its error) between kept neighbours. */
static size_t worst(const struct stray_curve_view *c, const char *kept,
		    double *err_dex)
{
	size_t i, lo = 0, best = 0;

	*err_dex = -1.0;
	for (i = 1; i < c->n; i++) {
		size_t j;

		if (!kept[i])
			continue;
		for (j = lo + 1; j < i; j++) {
			double e = gap(c, lo, i, j);

			if (e > *err_dex) {
				*err_dex = e;
				best = j;
			}
		}
		lo = i;
	}
	return best;
}

/* The two samples around the last fall below a (the exclusion crossing
 * the module and `stray exclusion` find between them): kept. */
static size_t keep_crossing(const struct stray_curve_view *c, double a,
			    char *kept)
{
	size_t i, added = 0;

	for (i = c->n - 1; i > 0; i--)
		if (c->alpha[i - 1] >= a) {
			added += !kept[i - 1] + !kept[i];
			kept[i - 1] = kept[i] = 1;
			break;
		}
	return added;
}

int fdrfw_curve_thin(const struct stray_curve_view *in,
		     const double *keep_crossings, size_t n_keep,
		     double *theta_deg, double *alpha,
		     struct stray_curve_view *out, struct fdrfw_thin_report *r,
		     struct stray_error *err)
{
	char *kept = calloc(in->n ? in->n : 1, 1);
	size_t n = 2, i, k = 0;

	r->rows_in = in->n;
	r->max_err_dex = 0.0;
	r->at_deg = NAN;
	if (in->n <= FDRFW_CURVE_MAX) {	/* as it is */
		free(kept);
		*out = *in;
		r->rows_out = in->n;
		return STRAY_OK;
	}
	if (!kept)
		return stray_error_set(err, STRAY_ENOMEM, "curve",
				       "out of memory");
	kept[0] = kept[in->n - 1] = 1;
	for (i = 0; i < n_keep && n + 2 <= FDRFW_CURVE_MAX; i++)
		n += keep_crossing(in, keep_crossings[i], kept);
	for (; n < FDRFW_CURVE_MAX; n++) {
		double e;

		kept[worst(in, kept, &e)] = 1;
	}
	r->at_deg = in->theta_deg[worst(in, kept, &r->max_err_dex)];
	for (i = 0; i < in->n; i++)
		if (kept[i]) {
			theta_deg[k] = in->theta_deg[i];
			alpha[k++] = in->alpha[i];
		}
	free(kept);
	out->n = k;
	out->theta_deg = theta_deg;
	out->alpha = alpha;
	out->sigma = NULL;
	r->rows_out = k;
	return STRAY_OK;
}

/*
 * The table from the curve, thinned to the table's rows when longer (the
 * default trace grid has 160-190 angles): a first pass gives the Sun's
 * alpha_req (it depends on the sensor, not the curve), the second keeps
 * the two samples around its crossing, so the table's Sun angle is the
 * whole curve's.
 */
int fdrfw_table_build_thinned(const struct stray_curve_view *v,
			      const struct stray_sensor *sensor,
			      const struct fdrfw_build_params *p,
			      struct fdrfw_table *t, struct stray_exclusion *sun,
			      struct fdrfw_thin_report *thin,
			      struct stray_error *err)
{
	double th[FDRFW_CURVE_MAX], al[FDRFW_CURVE_MAX];
	struct stray_curve_view tv;
	double req;
	int rc = fdrfw_curve_thin(v, NULL, 0, th, al, &tv, thin, err);

	if (rc == STRAY_OK)
		rc = fdrfw_table_build_verdict(&tv, sensor, p, t, sun, err);
	if (rc != STRAY_OK || thin->rows_in == thin->rows_out)
		return rc;
	req = (double)t->alpha_req_sun;
	rc = fdrfw_curve_thin(v, &req, 1, th, al, &tv, thin, err);
	return rc ? rc : fdrfw_table_build_verdict(&tv, sensor, p, t, sun, err);
}
