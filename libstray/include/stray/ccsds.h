/*
 * ccsds.h - what the CCSDS KVN readers (stray/oem.h, stray/aem.h) share:
 * epochs in the supported time systems, reduced to TT seconds since
 * J2000.0 (2000-01-01T12:00:00 TT), and the line splitter of the KVN form
 * (CCSDS 502.0-B-3 §7, 504.0-B-2 §6: "KEY = value", COMMENT lines, blank
 * lines, data lines of white-space separated fields).
 */
#ifndef STRAY_CCSDS_H
#define STRAY_CCSDS_H

#include <stddef.h>

#include "stray/error.h"

enum stray_time_system { STRAY_TS_UTC, STRAY_TS_TAI, STRAY_TS_TT,
			 STRAY_TS_GPS };

/* The time system named by text (UTC, TAI, TT, GPS); -1 if unsupported. */
int stray_ccsds_time_system(const char *text);

/* An inertial frame the readers accept (EME2000, ICRF, GCRF, J2000). */
int stray_ccsds_inertial_frame(const char *text);

/*
 * "YYYY-MM-DDThh:mm:ss[.f]" or "YYYY-DDDThh:mm:ss[.f]" (an optional
 * trailing Z) in time system ts, to TT seconds since J2000.0.  UTC takes
 * the leap seconds of 1972-2017 (TAI - UTC = 37 s since 2017-01-01).
 * Returns 0, -1 if the text is not an epoch, -2 if its second is 60 where
 * no leap second is (only UTC has them, at 23:59:60 of the days of the
 * table).
 */
int stray_ccsds_epoch(const char *text, int ts, double *t_tt);

/*
 * The gap rule (docs/limits.md): a step between records is a gap when it
 * is longer than the interpolation window's nominal span, (nodes - 1)
 * times the median step and never under 2 of them; interpolation never
 * crosses one.  stray_ccsds_gap_s gives that length for records t[0..n)
 * (-1 out of memory); stray_ccsds_gaps counts the gaps.
 */
double stray_ccsds_gap_s(const double *t, size_t n, size_t nodes);
size_t stray_ccsds_gaps(const double *t, size_t n, double gap_s);

/*
 * The records around `at` that interpolation may use: t[*lo .. *hi], no
 * gap among them, at most `reach` records to either side of the step
 * holding `at`.  Returns 0, or -1 when `at` is outside t[0 .. n-1] or
 * inside a gap (a record on a gap's edge is covered, alone if need be).
 */
int stray_ccsds_piece(const double *t, size_t n, double gap_s, double at,
		      size_t reach, size_t *lo, size_t *hi);

/* Days from 2000-01-01 to the civil date y-m-d (negative before). */
long stray_ccsds_days_from_2000(long y, long m, long d);

/* The inverse for writing: t_tt to "YYYY-MM-DDThh:mm:ss.ffffff" in ts. */
void stray_ccsds_format_epoch(double t_tt, int ts, char *buf, size_t size);

/* A finite decimal number, [+-]d[.d][E[+-]d] and nothing after it (no
 * hex float, INF or NAN, which strtod alone takes): 1, else 0. */
int stray_kvn_number(const char *s, double *x);

/* One KVN line split in place (the line buffer is modified). */
struct stray_kvn_line {
	int kind;		/* STRAY_KVN_* */
	char *key, *value;	/* KEY = value */
	char *field[16];	/* data fields */
	int n_field;
};
enum { STRAY_KVN_BLANK, STRAY_KVN_COMMENT, STRAY_KVN_KEYVAL,
       STRAY_KVN_DATA, STRAY_KVN_WORD };

/*
 * Split the next line of buf[*pos .. len) into line (copied into scratch
 * of size scratch_size, a line longer than that is an error); *lineno
 * counts lines.  Returns 1 for a line, 0 at the end, -1 for a line too
 * long or holding a NUL byte (err names file and line).
 */
int stray_kvn_next(const char *buf, size_t len, size_t *pos, long *lineno,
		   char *scratch, size_t scratch_size,
		   struct stray_kvn_line *line, const char *file,
		   struct stray_error *err);

/*
 * Feed each line of buf[0 .. len) but blank and COMMENT ones to
 * fn(ctx, line), in order, until fn returns other than STRAY_OK;
 * *lineno counts lines (for fn's own messages).  Returns STRAY_OK, what
 * fn returned, or STRAY_EPARSE for a line stray_kvn_next refuses.
 */
int stray_kvn_each(const char *buf, size_t len, const char *file,
		   long *lineno,
		   int (*fn)(void *ctx, const struct stray_kvn_line *line),
		   void *ctx, struct stray_error *err);

/* A keyword of the message header the readers pass over (CREATION_DATE,
 * ORIGINATOR, MESSAGE_ID): 1, else 0. */
int stray_kvn_header_key(const char *key);

/* Sets err to "file:line: keyword `key`: why" with text; STRAY_EPARSE. */
int stray_kvn_fail(struct stray_error *err, const char *file, long line,
		   const char *key, const char *why, const char *text);

#endif /* STRAY_CCSDS_H */
