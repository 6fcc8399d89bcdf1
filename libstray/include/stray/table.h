/*
 * table.h - numeric CSV tables with `#` comment lines (hosted).
 *
 * The one reader behind every CSV the toolkit takes (docs/formats.md):
 * comment lines start with '#', and `# key: value` lines are kept as
 * metadata; a header row names the columns; every other cell must be a
 * finite number.  Fields are split by libcsv.  A bad cell is reported with
 * its file, line and column name.
 */
#ifndef STRAY_TABLE_H
#define STRAY_TABLE_H

#include <stddef.h>
#include <stdio.h>

#include "stray/error.h"

/* Input limits (docs/limits.md): a table longer than this is refused. */
#define STRAY_TABLE_ROWS_MAX 100000

struct stray_table {
	size_t n_rows, n_cols;
	char **col;		/* n_cols column names */
	double *cell;		/* n_rows * n_cols, row-major */
	long *line;		/* source line of each row (1-based) */
	char **meta;		/* comment lines without the leading '#' */
	size_t n_meta;
};

/*
 * Parse a table from memory; name is used in error messages (the file
 * name).  On failure the table is left empty and err names the place.
 */
int stray_table_parse(const char *name, const char *text, size_t len,
		      struct stray_table *t, struct stray_error *err);

/* Read and parse a file. */
int stray_table_read(const char *path, struct stray_table *t,
		     struct stray_error *err);

/* Release everything a table owns; safe on an empty or zeroed table. */
void stray_table_free(struct stray_table *t);

/* Index of a column by name, or -1. */
int stray_table_find(const struct stray_table *t, const char *name);

/* A column copied out into a new array (caller frees), NULL on ENOMEM. */
double *stray_table_column(const struct stray_table *t, size_t col);

/* Value of a `# key: value` metadata line, or NULL. */
const char *stray_table_meta(const struct stray_table *t, const char *key);

#endif /* STRAY_TABLE_H */
