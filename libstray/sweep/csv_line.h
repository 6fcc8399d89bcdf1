/*
 * csv_line.h - private to libstray/sweep: one line of a sweep folder's
 * CSV files (manifest.csv, a lab's import log) split into its cells by
 * libcsv, strictly (RFC 4180 quoting), into fixed-size cells.
 */
#ifndef STRAY_SWEEP_CSV_LINE_H
#define STRAY_SWEEP_CSV_LINE_H

#include <stddef.h>

#include "stray/error.h"

#define CSV_LINE_FIELDS_MAX 32
#define CSV_LINE_FIELD_LEN_MAX 512

struct csv_line {
	size_t n;
	char f[CSV_LINE_FIELDS_MAX][CSV_LINE_FIELD_LEN_MAX];
	int overflow;
};

/* Split line `line` of file `name` (s, len bytes, no newline) into r;
 * STRAY_EPARSE naming the file and line for bad quoting or more or
 * longer cells than r holds, STRAY_ENOMEM. */
int csv_line_split(const char *name, long line, const char *s, size_t len,
		   struct csv_line *r, struct stray_error *err);

#endif /* STRAY_SWEEP_CSV_LINE_H */
