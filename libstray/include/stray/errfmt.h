/*
 * errfmt.h - hosted helpers of the error path: attach the file, line and
 * offending text to a record, and format it as the one stderr line.
 */
#ifndef STRAY_ERRFMT_H
#define STRAY_ERRFMT_H

#include <stddef.h>

#include "stray/error.h"

/* Attach where the error happened (file may be NULL; line 0 = none). */
void stray_error_locate(struct stray_error *err, const char *file, long line);

/* Attach the offending text (truncated to fit). */
void stray_error_text(struct stray_error *err, const char *text);

/* Name the field by a run-time string (a column or key), copied. */
void stray_error_column(struct stray_error *err, const char *name);

/* Record an error with a file and line; returns code. */
int stray_error_at(struct stray_error *err, int code, const char *file,
		   long line, const char *field, const char *reason);

/*
 * One line, git style: "<file>:<line>: <field> '<value>': <reason>".
 * Parts that are unknown are left out.  Returns buf.
 */
char *stray_error_format(const struct stray_error *err, char *buf,
			 size_t size);

#endif /* STRAY_ERRFMT_H */
