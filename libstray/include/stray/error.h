/*
 * error.h - the one error path of libstray.
 *
 * Fallible functions return an int status (0 = STRAY_OK) and, given a
 * caller-owned struct stray_error, record what failed: the code, the field,
 * the offending value and a static reason.  The first error wins, so a
 * low-level failure is not overwritten by the caller's more generic one
 * (SQLite's sqlite3ErrorWithMsg / nanopb's PB_RETURN_ERROR).  The core only
 * stores static strings and a number; the hosted layer adds the file, line
 * and offending text and formats the one-line message (stray_error_format).
 */
#ifndef STRAY_ERROR_H
#define STRAY_ERROR_H

#include <stddef.h>

#include "stray/config.h"

enum stray_status {
	STRAY_OK = 0,
	STRAY_EINVAL,	/* a value is out of its domain (bad input) */
	STRAY_EPARSE,	/* a file or text is malformed (bad input) */
	STRAY_ENOTFOUND,	/* a name, key or column is unknown (bad input) */
	STRAY_ERANGE,	/* a result does not exist in the range searched */
	STRAY_ENOCONV,	/* an iteration did not converge in its bound */
	STRAY_EIO,	/* a file could not be read or written */
	STRAY_ENOMEM,	/* out of memory (hosted layer only) */
	STRAY_STATUS_COUNT
};

#define STRAY_ERROR_FILE_MAX 256
#define STRAY_ERROR_TEXT_MAX 96
#define STRAY_ERROR_COLUMN_MAX 64

struct stray_error {
	int code;		/* enum stray_status */
	const char *field;	/* static: parameter, key or column name */
	const char *reason;	/* static: what is wrong with it */
	stray_real value;	/* the offending number, when has_value */
	int has_value;
	/* Filled by the hosted layer only. */
	long line;		/* 1-based line in file, 0 when none */
	char file[STRAY_ERROR_FILE_MAX];
	char column[STRAY_ERROR_COLUMN_MAX];	/* a field named at run time */
	char text[STRAY_ERROR_TEXT_MAX];	/* offending text, may be "" */
};

/* Reset a record to "no error". */
void stray_error_clear(struct stray_error *err);

/*
 * Record an error unless one is already recorded; err may be NULL.
 * Returns code, so a caller can write `return stray_error_set(...)`.
 */
int stray_error_set(struct stray_error *err, int code, const char *field,
		    const char *reason);

/* As stray_error_set, with the offending numeric value. */
int stray_error_set_value(struct stray_error *err, int code,
			  const char *field, const char *reason,
			  stray_real value);

/* Static text of a status code; never NULL. */
const char *stray_status_text(int code);

/* True for codes that mean the caller's input was bad (CLI exit status 2). */
int stray_status_is_bad_input(int code);

#endif /* STRAY_ERROR_H */
