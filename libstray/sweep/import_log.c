/*
 * import_log.c - the lab's CSV log of a sweep taken by other software
 * (sweep_import.h), read through libcsv as manifest.csv is: one row per
 * frame file with its angle, frame type, exposure and ND transmission,
 * every value checked here so the import only compares.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "csv_line.h"
#include "stray/errfmt.h"
#include "stray/sweep_import.h"
#include "stray/sweep_store.h"


/* The ND is one of two columns: its transmission or its optical
 * density. */
enum { C_FILE, C_ANGLE, C_TYPE, C_EXP, N_REQ, C_ND = N_REQ, C_OD,
       C_RB, C_FILTER, C_DATE, C_MON, N_COLS };

static const char *const names[N_COLS] = {
	STRAY_IMPORT_COL_FILE, STRAY_IMPORT_COL_ANGLE, STRAY_IMPORT_COL_TYPE,
	STRAY_IMPORT_COL_EXPTIME, STRAY_IMPORT_COL_NDTRANS,
	STRAY_IMPORT_COL_ND_OD, STRAY_IMPORT_COL_READBACK,
	STRAY_IMPORT_COL_FILTER, STRAY_IMPORT_COL_DATE,
	STRAY_IMPORT_COL_MONITOR
};

/* Other names a lab's log may give a column (any case): the manifest's
 * names are ours, these are the ones acquisition scripts write. */
static const char *const aliases[N_COLS][4] = {
	{ "filename", NULL },
	{ "angle", "theta_deg", "theta", NULL },
	{ "frame_type", "type", "imagetyp", NULL },
	{ "exptime", "exposure", "exposure_s", NULL },
	{ "nd_trans", "nd_transmission", NULL },
	{ "nd_density", NULL },
	{ "readback", "angle_readback_deg", NULL },
	{ NULL }, { "date", "date-obs", NULL }, { NULL }
};

static int bad(const char *name, long line, const char *col,
	       const char *reason, const char *text, struct stray_error *err)
{
	stray_error_at(err, STRAY_EPARSE, name, line, col, reason);
	stray_error_text(err, text);
	return STRAY_EPARSE;
}

/* A finite number; "nan", "inf" and "1e999" are not. */
static int number(const char *name, long line, int col, const char *s,
		  double *v, struct stray_error *err)
{
	char *end;

	errno = 0;
	*v = strtod(s, &end);
	while (*end == ' ')
		end++;
	if (*s == '\0' || *end != '\0' || !isfinite(*v))
		return bad(name, line, names[col], "is not a finite number", s,
			   err);
	return STRAY_OK;
}

/* A plain name (the files are matched by name, never opened by it). */
static int plain_name(const char *name, long line, const char *s,
		      struct stray_error *err)
{
	const char *c;

	for (c = s; *c; c++)
		if (*c == '/' || (unsigned char)*c < 0x20 || *c == 0x7f)
			break;
	if (*s == '\0' || *c != '\0' || strcmp(s, ".") == 0 ||
	    strcmp(s, "..") == 0 || strlen(s) >= STRAY_SWEEP_FILE_MAX)
		return bad(name, line, names[C_FILE], "must be a plain file "
			   "name (no '/'), as the file is named on disk", s,
			   err);
	return STRAY_OK;
}

static int frame_type(const char *name, long line, const char *s, int *type,
		      struct stray_error *err)
{
	static const char *const t[] = { "DARK", "AMBIENT", "FULL" };
	int k;

	for (k = 0; k < 3; k++)
		if (strcasecmp(s, t[k]) == 0) {
			*type = k;	/* enum stray_sweep_frametyp */
			return STRAY_OK;
		}
	return bad(name, line, names[C_TYPE], "must be DARK, AMBIENT (beam "
		   "blocked) or FULL (beam on the aperture)", s, err);
}

/* An optional cell: "" (or no cell) is absent. */
static const char *cell(const struct csv_line *r, const int *idx, int c)
{
	return idx[c] >= 0 && (size_t)idx[c] < r->n ? r->f[idx[c]] : "";
}

static int optional(const char *name, long line, const struct csv_line *r,
		    const int *idx, struct stray_import_row *e,
		    struct stray_error *err)
{
	const char *s;
	int rc;

	e->readback_deg = e->date_obs = e->monitor = NAN;
	e->filter[0] = '\0';
	if (*(s = cell(r, idx, C_RB))) {
		if ((rc = number(name, line, C_RB, s, &e->readback_deg, err)))
			return rc;
		if (fabs(e->readback_deg) > 180.0)
			return bad(name, line, names[C_RB],
				   "must be within -180..180", s, err);
	}
	if (*(s = cell(r, idx, C_DATE)) &&
	    stray_sweep_utc_parse(s, &e->date_obs) != STRAY_OK)
		return bad(name, line, names[C_DATE], "must be a UTC time "
			   "like 2026-12-02T04:50:00.123Z", s, err);
	if (*(s = cell(r, idx, C_MON))) {
		if ((rc = number(name, line, C_MON, s, &e->monitor, err)))
			return rc;
		if (!(e->monitor > 0.0))
			return bad(name, line, names[C_MON], "must be > 0 "
				   "(the lamp level, 1 = nominal)", s, err);
	}
	if (idx[C_MON] >= 0 && isnan(e->monitor))
		return bad(name, line, names[C_MON], "is empty: a log with "
			   "the column gives every frame's level", s, err);
	s = cell(r, idx, C_FILTER);
	if (strlen(s) >= sizeof(e->filter))
		return bad(name, line, names[C_FILTER], "is longer than 71 "
			   "characters (a FITS string)", s, err);
	strcpy(e->filter, s);
	return STRAY_OK;
}

static int take_row(const char *name, long line, const struct csv_line *r,
		    const int *idx, struct stray_import_row *e,
		    struct stray_error *err)
{
	int rc;

	memset(e, 0, sizeof(*e));
	e->line = line;
	if ((rc = plain_name(name, line, r->f[idx[C_FILE]], err)) ||
	    (rc = frame_type(name, line, r->f[idx[C_TYPE]], &e->type, err)) ||
	    (rc = number(name, line, C_ANGLE, r->f[idx[C_ANGLE]],
			 &e->angle_deg, err)) ||
	    (rc = number(name, line, C_EXP, r->f[idx[C_EXP]], &e->exptime_s,
			 err)) ||
	    (rc = idx[C_ND] >= 0 ? number(name, line, C_ND, r->f[idx[C_ND]],
					   &e->ndtrans, err)
		 : number(name, line, C_OD, r->f[idx[C_OD]], &e->ndtrans,
			  err)))
		return rc;
	if (idx[C_ND] < 0) {	/* an optical density d: 10^-d */
		if (!(e->ndtrans >= 0.0 && e->ndtrans <= 12.0))
			return bad(name, line, names[C_OD], "must be in 0..12 "
				   "(an optical density)", r->f[idx[C_OD]],
				   err);
		e->ndtrans = pow(10.0, -e->ndtrans);
	}
	strcpy(e->file, r->f[idx[C_FILE]]);
	if (fabs(e->angle_deg) > 180.0)
		return bad(name, line, names[C_ANGLE],
			   "must be within -180..180", r->f[idx[C_ANGLE]], err);
	if (!(e->exptime_s > 0.0))
		return bad(name, line, names[C_EXP], "must be > 0",
			   r->f[idx[C_EXP]], err);
	if (!(e->ndtrans > 0.0 && e->ndtrans <= 1.0))
		return bad(name, line, names[C_ND], "must be in (0, 1] (the "
			   "transmission; or give the optical density as "
			   "nd_od)", r->f[idx[C_ND]], err);
	return optional(name, line, r, idx, e, err);
}

static int is_name(const char *cell, int c)
{
	int a;

	if (strcasecmp(cell, names[c]) == 0)
		return 1;
	for (a = 0; a < 4 && aliases[c][a]; a++)
		if (strcasecmp(cell, aliases[c][a]) == 0)
			return 1;
	return 0;
}

static int take_header(const char *name, long line, const struct csv_line *r,
		       int *idx, struct stray_error *err)
{
	size_t k;
	int c, nd = 0;

	for (c = 0; c < N_COLS; c++) {
		idx[c] = -1;
		for (k = 0; k < r->n; k++)
			if (is_name(r->f[k], c)) {
				if (idx[c] >= 0)
					return bad(name, line, names[c],
						   "column named twice",
						   r->f[k], err);
				idx[c] = (int)k;
			}
		if (c < N_REQ && idx[c] < 0)
			return stray_error_at(err, STRAY_ENOTFOUND, name, line,
				names[c], "column missing from the header (file,"
				"angle_deg,frametyp,exptime_s,ndtrans)");
	}
	for (k = 0; k < r->n; k++)
		nd |= strcasecmp(r->f[k], "nd") == 0;
	if (idx[C_ND] >= 0 && idx[C_OD] >= 0)
		return bad(name, line, names[C_ND], "and nd_od both given: "
			   "one ND column", names[C_OD], err);
	if (idx[C_ND] < 0 && idx[C_OD] < 0)
		return stray_error_at(err, STRAY_ENOTFOUND, name, line,
			names[C_ND], nd ? "column 'nd' is ambiguous: name it "
			"ndtrans (the transmission, 1 = none) or nd_od (the "
			"optical density, 0 = none)" : "column missing from "
			"the header (file,angle_deg,frametyp,exptime_s,"
			"ndtrans)");
	return STRAY_OK;
}

static int push(struct stray_import_log *log, const char *name, long line,
		struct stray_error *err)
{
	struct stray_import_row *p;
	size_t cap;

	if (log->n < log->cap)
		return STRAY_OK;
	if (log->n >= STRAY_IMPORT_ROWS_MAX)
		return stray_error_at(err, STRAY_EINVAL, name, line, "row",
				      "more than 100000 frames in one log");
	cap = log->cap ? 2 * log->cap : 64;
	p = realloc(log->r, cap * sizeof(*p));
	if (!p)
		return stray_error_at(err, STRAY_ENOMEM, name, line, 0, 0);
	log->r = p;
	log->cap = cap;
	return STRAY_OK;
}

static int take_line(const char *name, long line, const char *s, size_t len,
		     struct stray_import_log *log, int *idx, int *have_header,
		     struct csv_line *r, struct stray_error *err)
{
	size_t k = 0;
	int rc;

	if (len > 0 && s[len - 1] == '\r')
		len--;
	while (k < len && (s[k] == ' ' || s[k] == '\t'))
		k++;
	if (k == len || s[k] == '#')
		return STRAY_OK;
	if ((rc = csv_line_split(name, line, s, len, r, err)) != STRAY_OK)
		return rc;
	if (!*have_header) {
		*have_header = 1;
		return take_header(name, line, r, idx, err);
	}
	for (k = 0; k < C_RB; k++)	/* the required and the ND */
		if (idx[k] >= 0 && (size_t)idx[k] >= r->n)
			return stray_error_at(err, STRAY_EPARSE, name, line,
					      names[k], "cell missing (fewer "
					      "cells than the header)");
	if ((rc = push(log, name, line, err)) != STRAY_OK)
		return rc;
	rc = take_row(name, line, r, idx, &log->r[log->n], err);
	if (rc == STRAY_OK)
		log->n++;
	return rc;
}

/* One row per file: a second row for it is named at its line. */
static int no_duplicates(const char *name, const struct stray_import_log *log,
			 struct stray_error *err)
{
	size_t dup;

	if (stray_sweep_repeated_file(log->r, log->n, sizeof(*log->r),
			offsetof(struct stray_import_row, file),
			offsetof(struct stray_import_row, line), &dup))
		return stray_error_at(err, STRAY_ENOMEM, name, 0, 0, 0);
	if (dup < log->n)
		return bad(name, log->r[dup].line, names[C_FILE], "is logged "
			   "twice (one row per frame file)", log->r[dup].file,
			   err);
	return STRAY_OK;
}

int stray_import_log_parse(const char *name, const char *text, size_t len,
			   struct stray_import_log *log,
			   struct stray_error *err)
{
	struct csv_line *r = malloc(sizeof(*r));
	int idx[N_COLS], have_header = 0, rc = STRAY_OK;
	size_t pos = 0;
	long line = 0;

	memset(log, 0, sizeof(*log));
	if (!r)
		return stray_error_at(err, STRAY_ENOMEM, name, 0, 0, 0);
	while (pos < len && rc == STRAY_OK) {
		const char *nl = memchr(text + pos, '\n', len - pos);
		size_t end = nl ? (size_t)(nl - text) : len;

		rc = take_line(name, ++line, text + pos, end - pos, log, idx,
			       &have_header, r, err);
		pos = end + 1;
	}
	free(r);
	if (rc == STRAY_OK && log->n == 0)
		rc = stray_error_at(err, STRAY_EPARSE, name, line ? line : 1,
				    names[C_FILE], have_header ? "the log lists "
				    "no frames" : "the log has no header line");
	if (rc == STRAY_OK)
		rc = no_duplicates(name, log, err);
	if (rc != STRAY_OK) {
		stray_import_log_free(log);
		return rc;
	}
	log->has_readback = idx[C_RB] >= 0;
	log->has_filter = idx[C_FILTER] >= 0;
	log->has_date = idx[C_DATE] >= 0;
	log->has_monitor = idx[C_MON] >= 0;
	return STRAY_OK;
}

void stray_import_log_free(struct stray_import_log *log)
{
	free(log->r);
	memset(log, 0, sizeof(*log));
}
