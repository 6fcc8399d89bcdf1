/*
 * frames_plot.c - the validation figure of `stray frames` (issue 13 item
 * 6): false stars per image measured on rendered frames against the
 * predictions, before (eq. 2.18) and after the extension, per detector,
 * with the line of agreement and the factor-1.5 band.
 */
#include <math.h>
#include <stdlib.h>

#include "frames_plot.h"
#include "plot.h"
#include "stray/errfmt.h"
#include "stray/table.h"

static const char *const cols[] = { "model_fdr", "measured_thesis",
	"sigma_thesis", "extended_thesis", "measured_threshold",
	"sigma_threshold", "extended_threshold" };
enum { MODEL, M_TH, S_TH, E_TH, M_PX, S_PX, E_PX, N_COLS };

int frames_plot_validation(const char *csv, const char *png,
			   struct stray_error *err)
{
	struct stray_table t;
	double *v[N_COLS] = { 0 }, *lo[2] = { 0 }, *hi[2] = { 0 };
	double line[2] = { 1e-3, 1e5 }, up[2], dn[2];
	size_t i, n;
	int c, k, rc = stray_table_read(csv, &t, err);

	if (rc != STRAY_OK)
		return rc;
	n = t.n_rows;
	for (c = 0; c < N_COLS && rc == STRAY_OK; c++) {
		int j = stray_table_find(&t, cols[c]);

		if (j < 0)
			rc = stray_error_at(err, STRAY_EPARSE, csv, 0, cols[c],
					    "required column is missing");
		else if (!(v[c] = stray_table_column(&t, (size_t)j)))
			rc = stray_error_set(err, STRAY_ENOMEM, "table", "no memory");
	}
	for (k = 0; k < 2 && rc == STRAY_OK; k++) {
		lo[k] = malloc(n * sizeof(double));
		hi[k] = malloc(n * sizeof(double));
		if (!lo[k] || !hi[k])
			rc = stray_error_set(err, STRAY_ENOMEM, "table", "no memory");
		for (i = 0; rc == STRAY_OK && i < n; i++) {
			double m = v[k ? M_PX : M_TH][i], s = v[k ? S_PX : S_TH][i];

			lo[k][i] = fmax(m - s, 1e-3);
			hi[k][i] = m + s;
		}
	}
	for (k = 0; k < 2; k++) {
		up[k] = line[k] * 1.5;
		dn[k] = line[k] / 1.5;
	}
	if (rc == STRAY_OK) {
		const struct plot_series s[] = {
			{ v[MODEL], v[M_TH], n, lo[0], hi[0], PLOT_GREY, PLOT_POINTS,
			  "thesis detector vs eq. 2.18" },
			{ v[E_TH], v[M_TH], n, lo[0], hi[0], PLOT_BLUE, PLOT_POINTS,
			  "thesis detector vs extended (sliding window)" },
			{ v[MODEL], v[M_PX], n, lo[1], hi[1], PLOT_ORANGE, PLOT_POINTS,
			  "threshold detector vs eq. 2.18" },
			{ v[E_PX], v[M_PX], n, lo[1], hi[1], PLOT_RED, PLOT_POINTS,
			  "threshold detector vs extended (pixel clusters)" },
			{ line, line, 2, NULL, NULL, PLOT_BLACK, PLOT_LINE,
			  "measured = predicted" },
			{ line, up, 2, NULL, NULL, PLOT_GREY, PLOT_DOTTED,
			  "factor 1.5" },
			{ line, dn, 2, NULL, NULL, PLOT_GREY, PLOT_DOTTED, NULL },
		};
		struct plot_spec p = { png,
			"False stars on rendered frames: measured vs predicted",
			"predicted false stars per image",
			"measured false stars per image", 1, 1, 1e-3, 1e5, 1e-3,
			1e5, s, 7, 1 };	/* legend below the diagonal: there
					 * the models over-predict, and none does */

		rc = plot_render(&p, err);
	}
	for (c = 0; c < N_COLS; c++)
		free(v[c]);
	for (k = 0; k < 2; k++) {
		free(lo[k]);
		free(hi[k]);
	}
	stray_table_free(&t);
	return rc;
}
