/*
 * curve_io.c - the attenuation-curve CSV (docs/formats.md): load with
 * validation that names file, line and column; save atomically with the
 * metadata and extra columns kept.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/curve_io.h"
#include "stray/provenance.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/table.h"

static int nomem(struct stray_error *err)
{
	return stray_error_set(err, STRAY_ENOMEM, 0, 0);
}

static int bad_value(struct stray_error *err, const char *name, long line,
		     const char *field, const char *reason, double v)
{
	char text[32];

	stray_error_at(err, STRAY_EPARSE, name, line, field, reason);
	snprintf(text, sizeof(text), "%.6g", v);
	stray_error_text(err, text);
	return STRAY_EPARSE;
}

/*
 * Row-wise checks with line numbers (curve.h's check has none), and the
 * physics of a curve (docs/limits.md): theta_deg in [0, 180], alpha >= 0,
 * alpha(0) = 1 where 0 is given (alpha is normalised by the on-axis beam,
 * docs/normalisation.md), and some alpha > 0 (an all-zero curve would seal
 * a flight table that never flags the Sun).
 */
static int check_rows(const char *name, const struct stray_table *t,
		      int c_theta, int c_alpha, int c_sigma,
		      struct stray_error *err)
{
	size_t i;
	int any_light = 0, off_axis = 0, off_axis_light = 0;

	for (i = 0; i < t->n_rows; i++) {
		const double *row = t->cell + i * t->n_cols;

		if (!(row[c_theta] >= 0.0 && row[c_theta] <= 180.0))
			return bad_value(err, name, t->line[i], "theta_deg",
					 "must be in [0, 180] degrees",
					 row[c_theta]);
		if (i > 0 && !(row[c_theta] > t->cell[(i - 1) * t->n_cols +
						      (size_t)c_theta]))
			return stray_error_at(err, STRAY_EPARSE, name,
				t->line[i], "theta_deg",
				"angles must be strictly increasing");
		if (row[c_alpha] < 0.0)
			return stray_error_at(err, STRAY_EPARSE, name,
				t->line[i], "alpha", "must be >= 0");
		if (c_sigma >= 0 && row[c_sigma] < 0.0)
			return stray_error_at(err, STRAY_EPARSE, name,
				t->line[i], "sigma", "must be >= 0");
		if (row[c_theta] == 0.0) {
			/* 5 % or 3 sigma: a drift-corrected reduction is
			 * only near 1; a mis-normalised curve is far off */
			double tol = c_sigma >= 0 ? 3.0 * row[c_sigma] : 0.0;

			if (tol < 0.05)
				tol = 0.05;
			if (fabs(row[c_alpha] - 1.0) > tol)
				return bad_value(err, name, t->line[i], "alpha",
					"must be 1 at theta_deg 0 (normalised "
					"by the on-axis beam)", row[c_alpha]);
		}
		any_light |= row[c_alpha] > 0.0;
		off_axis |= row[c_theta] > 0.0;
		off_axis_light |= row[c_theta] > 0.0 && row[c_alpha] > 0.0;
	}
	if (!any_light)
		return stray_error_at(err, STRAY_EPARSE, name, 0, "alpha",
				      "every value is 0 (an all-zero curve is "
				      "not a measurement)");
	/* a curve must show a baffle, not a spike: light on axis alone
	 * would seal a Sun exclusion inside the first step (1 deg) */
	if (off_axis && !off_axis_light)
		return stray_error_at(err, STRAY_EPARSE, name, 0, "alpha",
				      "every value beyond theta_deg 0 is 0 (a "
				      "spike on axis, not a baffle's curve)");
	return STRAY_OK;
}

static int take_columns(const struct stray_table *t, int c_theta,
			int c_alpha, int c_sigma, struct stray_curve *c,
			struct stray_error *err)
{
	size_t k;

	c->n = t->n_rows;
	c->theta_deg = stray_table_column(t, (size_t)c_theta);
	c->alpha = stray_table_column(t, (size_t)c_alpha);
	if (!c->theta_deg || !c->alpha)
		return nomem(err);
	if (c_sigma >= 0 && !(c->sigma = stray_table_column(t, (size_t)c_sigma)))
		return nomem(err);
	for (k = 0; k < t->n_cols; k++) {
		if ((int)k == c_theta || (int)k == c_alpha || (int)k == c_sigma)
			continue;
		if (c->n_extra == STRAY_CURVE_EXTRA_MAX)
			return stray_error_set(err, STRAY_EPARSE, "columns",
					       "more than 16 extra columns");
		c->extra_name[c->n_extra] = strdup(t->col[k]);
		c->extra[c->n_extra] = stray_table_column(t, k);
		if (!c->extra_name[c->n_extra] || !c->extra[c->n_extra])
			return nomem(err);
		c->n_extra++;
	}
	return STRAY_OK;
}

int stray_curve_parse(const char *name, const char *text, size_t len,
		      struct stray_curve *c, struct stray_error *err)
{
	struct stray_table t;
	int rc, c_theta, c_alpha, c_sigma;

	memset(c, 0, sizeof(*c));
	rc = stray_table_parse(name, text, len, &t, err);
	if (rc != STRAY_OK)
		return rc;
	c_theta = stray_table_find(&t, "theta_deg");
	c_alpha = stray_table_find(&t, "alpha");
	c_sigma = stray_table_find(&t, "sigma");
	if (c_theta < 0 || c_alpha < 0) {
		rc = stray_error_at(err, STRAY_EPARSE, name, 0,
			c_theta < 0 ? "theta_deg" : "alpha",
			"required column is missing");
		goto out_free_table;
	}
	if (t.n_rows == 0) {
		rc = stray_error_at(err, STRAY_EPARSE, name, 0, "alpha",
				    "curve has no rows");
		goto out_free_table;
	}
	rc = check_rows(name, &t, c_theta, c_alpha, c_sigma, err);
	if (rc == STRAY_OK)
		rc = take_columns(&t, c_theta, c_alpha, c_sigma, c, err);
	if (rc == STRAY_OK) {	/* the curve takes over the comment lines */
		c->meta = t.meta;
		c->n_meta = t.n_meta;
		t.meta = NULL;
		t.n_meta = 0;
	}
out_free_table:
	stray_table_free(&t);
	if (rc != STRAY_OK) {
		stray_error_locate(err, name, 0);
		stray_curve_free(c);
	}
	return rc;
}

int stray_curve_load(const char *path, struct stray_curve *c,
		     struct stray_error *err)
{
	char *buf;
	size_t len;
	int rc;

	memset(c, 0, sizeof(*c));
	rc = stray_file_read(path, &buf, &len, err);
	if (rc != STRAY_OK)
		return rc;
	rc = stray_curve_parse(path, buf, len, c, err);
	free(buf);
	return rc;
}

int stray_curve_alloc(struct stray_curve *c, size_t n, int with_sigma,
		      struct stray_error *err)
{
	memset(c, 0, sizeof(*c));
	c->n = n;
	c->theta_deg = calloc(n ? n : 1, sizeof(double));
	c->alpha = calloc(n ? n : 1, sizeof(double));
	if (with_sigma)
		c->sigma = calloc(n ? n : 1, sizeof(double));
	if (!c->theta_deg || !c->alpha || (with_sigma && !c->sigma)) {
		stray_curve_free(c);
		return nomem(err);
	}
	return STRAY_OK;
}

int stray_curve_add_column(struct stray_curve *c, const char *name,
			   const double *values, struct stray_error *err)
{
	double *v;

	if (c->n_extra == STRAY_CURVE_EXTRA_MAX)
		return stray_error_set(err, STRAY_EINVAL, "column",
				       "more than 16 extra columns");
	v = malloc((c->n ? c->n : 1) * sizeof(*v));
	if (!v)
		return nomem(err);
	memcpy(v, values, c->n * sizeof(*v));
	c->extra_name[c->n_extra] = strdup(name);
	if (!c->extra_name[c->n_extra]) {
		free(v);
		return nomem(err);
	}
	c->extra[c->n_extra++] = v;
	return STRAY_OK;
}

int stray_curve_add_meta(struct stray_curve *c, const char *key,
			 const char *value, struct stray_error *err)
{
	size_t len = strlen(key) + strlen(value) + 4;
	char **m = realloc(c->meta, (c->n_meta + 1) * sizeof(*m));

	if (!m)
		return nomem(err);
	c->meta = m;
	m[c->n_meta] = malloc(len);
	if (!m[c->n_meta])
		return nomem(err);
	snprintf(m[c->n_meta], len, " %s: %s", key, value);
	c->n_meta++;
	return STRAY_OK;
}

static void write_curve(FILE *f, const struct stray_curve *c)
{
	size_t i, k;

	/* this run's provenance; an input's own command and version lines
	 * described another run and are not carried over */
	if (stray_provenance_command()[0])
		fprintf(f, "# command: %s\n", stray_provenance_command());
	fprintf(f, "# version: stray %s\n", stray_provenance_version());
	for (i = 0; i < c->n_meta; i++)
		if (strncmp(c->meta[i], " command:", 9) &&
		    strncmp(c->meta[i], " version:", 9))
			fprintf(f, "#%s\n", c->meta[i]);
	fputs(c->sigma ? "theta_deg,alpha,sigma" : "theta_deg,alpha", f);
	for (k = 0; k < c->n_extra; k++)
		fprintf(f, ",%s", c->extra_name[k]);
	fputc('\n', f);
	for (i = 0; i < c->n; i++) {
		fprintf(f, "%.10g,%.10g", c->theta_deg[i], c->alpha[i]);
		if (c->sigma)
			fprintf(f, ",%.10g", c->sigma[i]);
		for (k = 0; k < c->n_extra; k++)
			fprintf(f, ",%.10g", c->extra[k][i]);
		fputc('\n', f);
	}
}

int stray_curve_save(const char *path, const struct stray_curve *c,
		     struct stray_error *err)
{
	struct stray_curve_view v = stray_curve_view_of(c);
	struct stray_file_out out;
	int rc = stray_curve_check(&v, err);

	if (rc != STRAY_OK) {
		stray_error_locate(err, path, 0);
		return rc;
	}
	rc = stray_file_open_atomic(&out, path, err);
	if (rc != STRAY_OK)
		return rc;
	write_curve(out.f, c);
	return stray_file_commit(&out, err);
}

struct stray_curve_view stray_curve_view_of(const struct stray_curve *c)
{
	struct stray_curve_view v = { c->n, c->theta_deg, c->alpha, c->sigma };

	return v;
}

void stray_curve_free(struct stray_curve *c)
{
	size_t i;

	for (i = 0; i < c->n_extra; i++) {
		free(c->extra_name[i]);
		free(c->extra[i]);
	}
	for (i = 0; i < c->n_meta; i++)
		free(c->meta[i]);
	free(c->meta);
	free(c->theta_deg);
	free(c->alpha);
	free(c->sigma);
	memset(c, 0, sizeof(*c));
}
