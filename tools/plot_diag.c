/*
 * plot_diag.c - the diagnosis as figures (PLplot through tools/plot.h):
 * PATH shows the measured curve with error bars and the model before and
 * after; PATH with "-resid" before the extension shows the log10
 * residuals before and after with their combined error bars.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag_report.h"
#include "plot.h"
#include "stray/errfmt.h"

static void resid_path(const char *path, char *out, size_t size)
{
	const char *dot = strrchr(path, '.');
	size_t stem = dot ? (size_t)(dot - path) : strlen(path);

	snprintf(out, size, "%.*s-resid%s", (int)stem, path, dot ? dot : ".png");
}

int diag_plot(const char *path, const struct diag_data *d,
	      const struct diag_result *r, struct stray_error *err)
{
	size_t n = d->n, i;
	double *b = malloc(6 * n * sizeof(*b)), amin = INFINITY;
	double *lo, *hi, *rlo_b, *rhi_b, *rlo_a, *rhi_a;
	char rpath[1024];
	int rc;

	if (!b)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	lo = b; hi = b + n; rlo_b = b + 2 * n; rhi_b = b + 3 * n;
	rlo_a = b + 4 * n; rhi_a = b + 5 * n;
	for (i = 0; i < n; i++) {
		lo[i] = fmax(d->alpha[i] - d->sigma[i], 0.5 * d->alpha[i]);
		hi[i] = d->alpha[i] + d->sigma[i];
		rlo_b[i] = r->resid_before[i] - r->rsig_before[i];
		rhi_b[i] = r->resid_before[i] + r->rsig_before[i];
		rlo_a[i] = r->resid_after[i] - r->rsig_after[i];
		rhi_a[i] = r->resid_after[i] + r->rsig_after[i];
		amin = fmin(amin, fmin(d->alpha[i], r->model_before[i] > 0 ?
				       r->model_before[i] : INFINITY));
	}
	{
		struct plot_series s[3] = {
			{ d->theta_deg, d->alpha, n, lo, hi, PLOT_BLACK,
			  PLOT_POINTS, "measured" },
			{ d->theta_deg, r->model_before, n, NULL, NULL,
			  PLOT_BLUE, PLOT_DASHED, "model before" },
			{ d->theta_deg, r->model_after, n, NULL, NULL,
			  PLOT_RED, PLOT_LINE, "model after" },
		};
		struct plot_spec p = { path, "stray diagnose: measured and model",
			"off-axis angle #gh [deg]", "attenuation #ga", 0, 1,
			NAN, NAN, amin / 3.0, 3.0, s, 3, 0 };

		rc = plot_render(&p, err);
	}
	if (!rc) {
		struct plot_series s[2] = {
			{ d->theta_deg, r->resid_before, n, rlo_b, rhi_b,
			  PLOT_BLUE, PLOT_POINTS, "before" },
			{ d->theta_deg, r->resid_after, n, rlo_a, rhi_a,
			  PLOT_RED, PLOT_POINTS, "after" },
		};
		struct plot_spec p = { rpath, "log#d10#u(measured / model)",
			"off-axis angle #gh [deg]", "residual", 0, 0,
			NAN, NAN, NAN, NAN, s, 2, 0 };

		resid_path(path, rpath, sizeof(rpath));
		rc = plot_render(&p, err);
	}
	free(b);
	return rc;
}
