/*
 * table.c - numeric CSV tables with '#' comments (docs/formats.md).
 *
 * Lines are taken one at a time so that comments are recognised and every
 * row keeps its line number for error messages; libcsv splits each data
 * line into fields (quoting, spaces), and strtod converts each field, which
 * must be consumed whole and be finite.
 */
#include <csv.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/table.h"

#define FIELDS_MAX 64
#define STR_(x) #x
#define STRAY_STR(x) STR_(x)

struct row_fields {
	size_t n;
	char *field[FIELDS_MAX];
	int overflow;
	int nomem;
};

static void on_field(void *data, size_t len, void *ctx)
{
	struct row_fields *r = ctx;
	char *s;

	if (r->n >= FIELDS_MAX) {
		r->overflow = 1;
		return;
	}
	s = malloc(len + 1);
	if (!s) {
		r->nomem = 1;
		return;
	}
	memcpy(s, data ? data : "", len);
	s[len] = '\0';
	r->field[r->n++] = s;
}

static void on_row(int c, void *ctx)
{
	(void)c;
	(void)ctx;
}

static void fields_free(struct row_fields *r)
{
	while (r->n > 0)
		free(r->field[--r->n]);
	r->overflow = r->nomem = 0;
}

/* Split one line (no newline) into fields with libcsv. */
static int split_line(const char *name, long lineno, const char *s,
		      size_t len, struct row_fields *r, struct stray_error *err)
{
	struct csv_parser p;

	if (csv_init(&p, CSV_STRICT | CSV_STRICT_FINI) != 0)
		return stray_error_at(err, STRAY_ENOMEM, name, lineno, 0, 0);
	if (csv_parse(&p, s, len, on_field, on_row, r) != len ||
	    csv_fini(&p, on_field, on_row, r) != 0) {
		stray_error_at(err, STRAY_EPARSE, name, lineno, "csv",
			       csv_strerror(csv_error(&p)));
		csv_free(&p);
		return STRAY_EPARSE;
	}
	csv_free(&p);
	if (r->nomem)
		return stray_error_at(err, STRAY_ENOMEM, name, lineno, 0, 0);
	if (r->overflow)
		return stray_error_at(err, STRAY_EPARSE, name, lineno, "csv",
				      "more than 64 columns");
	return STRAY_OK;
}

static int push_meta(struct stray_table *t, const char *s, size_t len)
{
	char **m = realloc(t->meta, (t->n_meta + 1) * sizeof(*m));

	if (!m)
		return STRAY_ENOMEM;
	t->meta = m;
	m[t->n_meta] = malloc(len + 1);
	if (!m[t->n_meta])
		return STRAY_ENOMEM;
	memcpy(m[t->n_meta], s, len);
	m[t->n_meta][len] = '\0';
	t->n_meta++;
	return STRAY_OK;
}

static int take_header(const char *name, long lineno, struct row_fields *r,
		       struct stray_table *t, struct stray_error *err)
{
	size_t i, j;

	if (r->n == 0)		/* never a zero-width table (realloc(p, 0)) */
		return stray_error_at(err, STRAY_EPARSE, name, lineno,
				      "header", "no column names");
	for (i = 0; i < r->n; i++) {
		if (r->field[i][0] == '\0')
			return stray_error_at(err, STRAY_EPARSE, name, lineno,
					      "header", "empty column name");
		for (j = 0; j < i; j++)
			if (strcmp(r->field[i], r->field[j]) == 0) {
				stray_error_at(err, STRAY_EPARSE, name, lineno,
					       "header", "duplicate column name");
				stray_error_text(err, r->field[i]);
				return STRAY_EPARSE;
			}
	}
	t->col = malloc(r->n * sizeof(*t->col));
	if (!t->col)
		return stray_error_at(err, STRAY_ENOMEM, name, lineno, 0, 0);
	memcpy(t->col, r->field, r->n * sizeof(*t->col));
	t->n_cols = r->n;
	r->n = 0;		/* the table owns the names now */
	return STRAY_OK;
}

/* Convert one data row; cap is the row capacity of t->cell / t->line. */
static int take_row(const char *name, long lineno, struct row_fields *r,
		    struct stray_table *t, size_t *cap,
		    struct stray_error *err)
{
	size_t i;

	if (r->n != t->n_cols) {
		char got[48];

		snprintf(got, sizeof(got), "%zu cells, header has %zu", r->n,
			 t->n_cols);
		stray_error_at(err, STRAY_EPARSE, name, lineno, "row",
			       "wrong number of cells");
		stray_error_text(err, got);
		return STRAY_EPARSE;
	}
	if (t->n_rows == STRAY_TABLE_ROWS_MAX)
		return stray_error_at(err, STRAY_EPARSE, name, lineno, "row",
				      "more than " STRAY_STR(STRAY_TABLE_ROWS_MAX)
				      " rows (docs/limits.md)");
	if (t->n_rows == *cap) {
		size_t nc = *cap ? 2 * *cap : 64;
		double *cell = realloc(t->cell, nc * t->n_cols * sizeof(*cell));
		long *line;

		if (!cell)
			return stray_error_at(err, STRAY_ENOMEM, name, lineno, 0, 0);
		t->cell = cell;
		line = realloc(t->line, nc * sizeof(*line));
		if (!line)
			return stray_error_at(err, STRAY_ENOMEM, name, lineno, 0, 0);
		t->line = line;
		*cap = nc;
	}
	for (i = 0; i < t->n_cols; i++) {
		const char *s = r->field[i];
		char *end;
		double v;

		errno = 0;
		v = strtod(s, &end);
		if (*s == '\0' || end == s || *end != '\0' || !isfinite(v)) {
			stray_error_at(err, STRAY_EPARSE, name, lineno, NULL,
				       *s ? "is not a finite number" : "is empty");
			stray_error_column(err, t->col[i]);
			stray_error_text(err, s);
			return STRAY_EPARSE;
		}
		t->cell[t->n_rows * t->n_cols + i] = v;
	}
	t->line[t->n_rows++] = lineno;
	return STRAY_OK;
}

/* Handle one line: comment, header, blank, or data row. */
static int take_line(const char *name, long lineno, const char *s,
		     size_t len, struct stray_table *t, size_t *cap,
		     struct stray_error *err)
{
	struct row_fields r = { 0 };
	size_t k = 0;
	int rc;

	if (len > 0 && s[len - 1] == '\r')
		len--;
	if (lineno == 1 && len >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0) {
		s += 3;		/* a UTF-8 byte-order mark (spreadsheets) */
		len -= 3;
	}
	while (k < len && (s[k] == ' ' || s[k] == '\t' || s[k] == '\r'))
		k++;
	if (k == len)
		return STRAY_OK;	/* blank line */
	if (s[k] == '#') {
		if (push_meta(t, s + k + 1, len - k - 1) != STRAY_OK)
			return stray_error_at(err, STRAY_ENOMEM, name, lineno, 0, 0);
		return STRAY_OK;
	}
	rc = split_line(name, lineno, s, len, &r, err);
	if (rc == STRAY_OK)
		rc = t->col ? take_row(name, lineno, &r, t, cap, err)
			    : take_header(name, lineno, &r, t, err);
	fields_free(&r);
	return rc;
}

int stray_table_parse(const char *name, const char *text, size_t len,
		      struct stray_table *t, struct stray_error *err)
{
	size_t pos = 0, cap = 0;
	long lineno = 0;
	int rc = STRAY_OK;

	memset(t, 0, sizeof(*t));
	if (memchr(text, '\0', len))
		return stray_error_at(err, STRAY_EPARSE, name, 0, "file",
				      "contains a NUL byte (not a text file)");
	while (pos < len && rc == STRAY_OK) {
		const char *nl = memchr(text + pos, '\n', len - pos);
		size_t end = nl ? (size_t)(nl - text) : len;

		rc = take_line(name, ++lineno, text + pos, end - pos, t, &cap,
			       err);
		pos = end + 1;
	}
	if (rc == STRAY_OK && !t->col)
		rc = stray_error_at(err, STRAY_EPARSE, name, 0, "header",
				    "no header row");
	if (rc != STRAY_OK)
		stray_table_free(t);
	return rc;
}

int stray_table_read(const char *path, struct stray_table *t,
		     struct stray_error *err)
{
	char *buf;
	size_t len;
	int rc;

	memset(t, 0, sizeof(*t));
	rc = stray_file_read(path, &buf, &len, err);
	if (rc != STRAY_OK)
		return rc;
	rc = stray_table_parse(path, buf, len, t, err);
	free(buf);
	return rc;
}

void stray_table_free(struct stray_table *t)
{
	size_t i;

	for (i = 0; i < t->n_cols; i++)
		free(t->col[i]);
	for (i = 0; i < t->n_meta; i++)
		free(t->meta[i]);
	free(t->col);
	free(t->meta);
	free(t->cell);
	free(t->line);
	memset(t, 0, sizeof(*t));
}

int stray_table_find(const struct stray_table *t, const char *name)
{
	size_t i;

	for (i = 0; i < t->n_cols; i++)
		if (strcmp(t->col[i], name) == 0)
			return (int)i;
	return -1;
}

double *stray_table_column(const struct stray_table *t, size_t col)
{
	double *v = malloc((t->n_rows ? t->n_rows : 1) * sizeof(*v));
	size_t i;

	if (!v)
		return NULL;
	for (i = 0; i < t->n_rows; i++)
		v[i] = t->cell[i * t->n_cols + col];
	return v;
}

const char *stray_table_meta(const struct stray_table *t, const char *key)
{
	size_t i, k = strlen(key);

	for (i = 0; i < t->n_meta; i++) {
		const char *m = t->meta[i];

		while (*m == ' ')
			m++;
		if (strncmp(m, key, k) == 0 && m[k] == ':') {
			m += k + 1;
			while (*m == ' ')
				m++;
			return m;
		}
	}
	return NULL;
}
