/*
 * lens_model.c - the ideal lens and PST import (stray/lens_model.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/lens_model.h"
#include "stray/table.h"

#define DEG (3.14159265358979323846 / 180.0)

int stray_lens_ideal(double field_half_deg, struct stray_curve *out,
		     struct stray_error *err)
{
	size_t steps, n, i;
	char buf[96];
	int rc;

	if (!(field_half_deg > 0.0 && field_half_deg <= 80.0))
		return stray_error_set_value(err, STRAY_EINVAL, "field_half_deg",
			"must be in (0, 80] deg", field_half_deg);
	steps = (size_t)floor(field_half_deg / 0.25 + 1e-9);
	/* 0, 0.25, ... below the edge, the edge, the step, 90 */
	n = steps + 1 + (fabs(steps * 0.25 - field_half_deg) > 1e-9) + 2;
	rc = stray_curve_alloc(out, n, 0, err);
	if (rc)
		return rc;
	for (i = 0; i <= steps; i++)
		out->theta_deg[i] = i * 0.25;
	if (fabs(steps * 0.25 - field_half_deg) > 1e-9)
		out->theta_deg[i++] = field_half_deg;
	for (n = 0; n < i; n++)
		out->alpha[n] = pow(cos(out->theta_deg[n] * DEG), 4.0);
	out->theta_deg[i] = field_half_deg + 0.001;
	out->alpha[i++] = 0.0;
	out->theta_deg[i] = 90.0;
	out->alpha[i++] = 0.0;
	out->n = i;
	snprintf(buf, sizeof(buf), "ideal lens, field half-angle %g deg: "
		 "cos^4 inside, 0 beyond (no ghosts, no scatter)",
		 field_half_deg);
	rc = stray_curve_add_meta(out, "kind", "lens", err);
	if (!rc)
		rc = stray_curve_add_meta(out, "source", buf, err);
	if (rc)
		stray_curve_free(out);
	return rc;
}

/* The column named name, or an error naming the file and the column. */
static int column(const char *path, const struct stray_table *t,
		  const char *name, int *idx, struct stray_error *err)
{
	*idx = stray_table_find(t, name);
	if (*idx >= 0)
		return STRAY_OK;
	stray_error_at(err, STRAY_ENOTFOUND, path, 0, "column",
		       "not in the header (--theta-col / --pst-col name it)");
	stray_error_column(err, name);
	return STRAY_ENOTFOUND;
}

/* Row i's angle th and PST p against the rules of stray_lens_from_pst. */
static int check_row(const char *path, const struct stray_table *t, size_t i,
		     int ct, int cp, const char *theta_col, const char *pst_col,
		     struct stray_error *err)
{
	double th = t->cell[i * t->n_cols + ct], p = t->cell[i * t->n_cols + cp];
	const char *col = theta_col, *why = NULL;
	double v = th;

	if (!(th >= 0.0 && th < 90.0))
		why = "must be in [0, 90) deg";
	else if (i > 0 && !(th > t->cell[(i - 1) * t->n_cols + ct]))
		why = "angles must increase";
	else if (i == 0 && th != 0.0)
		why = "the first row must be theta 0: alpha is normalised on axis";
	if (!why) {
		col = pst_col;
		v = p;
		if (!(p >= 0.0))
			why = "must be >= 0";
		else if (i == 0 && !(p > 0.0))
			why = "must be > 0 on axis: alpha is normalised by it";
	}
	if (!why)
		return STRAY_OK;
	stray_error_set_value(err, STRAY_EINVAL, "column", why, v);
	stray_error_locate(err, path, t->line[i]);
	stray_error_column(err, col);
	return STRAY_EINVAL;
}

int stray_lens_from_pst(const char *path, const char *theta_col,
			const char *pst_col, enum stray_pst_input input,
			struct stray_curve *out, struct stray_error *err)
{
	struct stray_table t = { 0 };
	int rc, ct = 0, cp = 0;
	size_t i;
	char buf[160];

	memset(out, 0, sizeof(*out));
	rc = stray_table_read(path, &t, err);
	if (!rc)
		rc = column(path, &t, theta_col, &ct, err);
	if (!rc)
		rc = column(path, &t, pst_col, &cp, err);
	if (!rc && t.n_rows < 2)
		rc = stray_error_at(err, STRAY_EINVAL, path, 0, "rows",
				    "a PST table needs at least 2 angles");
	for (i = 0; !rc && i < t.n_rows; i++)
		rc = check_row(path, &t, i, ct, cp, theta_col, pst_col, err);
	if (!rc)
		rc = stray_curve_alloc(out, t.n_rows, 0, err);
	for (i = 0; !rc && i < t.n_rows; i++) {
		double th = t.cell[i * t.n_cols + ct];

		out->theta_deg[i] = th;
		out->alpha[i] = t.cell[i * t.n_cols + cp] / t.cell[cp] *
			(input == STRAY_PST_APERTURE ? cos(th * DEG) : 1.0);
	}
	snprintf(buf, sizeof(buf), "PST of %.100s (input irradiance %s)", path,
		 input == STRAY_PST_APERTURE ? "in the aperture plane"
					     : "across the beam");
	if (!rc)
		rc = stray_curve_add_meta(out, "kind", "lens", err);
	if (!rc)
		rc = stray_curve_add_meta(out, "source", buf, err);
	if (rc)
		stray_curve_free(out);
	stray_table_free(&t);
	return rc;
}
