/*
 * manifest.c - manifest.csv of a sweep folder (sweep_store.h) read
 * through libcsv, and the rows of one (angle, type) counted.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "csv_line.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sweep_store.h"
#include "sweep_priv.h"


static const char *const columns[] = {
	STRAY_SWEEP_COL_FILE, STRAY_SWEEP_COL_FRAMETYP, STRAY_SWEEP_COL_ANGLE,
	STRAY_SWEEP_COL_EXPTIME, STRAY_SWEEP_COL_NDTRANS,
	STRAY_SWEEP_COL_SEQNUM, STRAY_SWEEP_COL_SHA256
};
enum { COL_FILE, COL_TYPE, COL_ANGLE, COL_EXP, COL_ND, COL_SEQ, COL_SHA,
       N_COLS, COL_DATE = N_COLS };	/* COL_DATE: optional, -1 absent */

static int bad_cell(const char *name, long line, const char *col,
		    const char *reason, const char *text,
		    struct stray_error *err)
{
	stray_error_at(err, STRAY_EPARSE, name, line, col, reason);
	stray_error_text(err, text);
	return STRAY_EPARSE;
}

static int number(const char *name, long line, const char *col,
		  const char *s, double *v, struct stray_error *err)
{
	char *end;

	errno = 0;
	*v = strtod(s, &end);
	if (*s == '\0' || *end != '\0' || !isfinite(*v))
		return bad_cell(name, line, col, "is not a finite number", s,
				err);
	return STRAY_OK;
}

static int check_sha(const char *name, long line, const char *s,
		     struct stray_error *err)
{
	size_t i;

	for (i = 0; i < 64; i++)
		if (!isxdigit((unsigned char)s[i]))
			break;
	if (i != 64 || s[64] != '\0')
		return bad_cell(name, line, columns[COL_SHA],
				"is not 64 hexadecimal digits", s, err);
	return STRAY_OK;
}

/* A plain name inside the folder: no separator, no "..", no control
 * character; the name is later opened as is (never through cfitsio's
 * extended syntax, where "(", "[" and "!" are instructions). */
static int check_file(const char *name, long line, const char *s,
		      struct stray_error *err)
{
	const char *c;

	for (c = s; *c; c++)
		if (*c == '/' || (unsigned char)*c < 0x20 || *c == 0x7f)
			break;
	if (*s == '\0' || *c != '\0' || strstr(s, "..") ||
	    strcmp(s, ".") == 0 || strlen(s) >= STRAY_SWEEP_FILE_MAX)
		return bad_cell(name, line, columns[COL_FILE],
				"must be a plain file name inside the sweep "
				"folder (no '/', no '..')", s, err);
	return STRAY_OK;
}

static int take_entry(const char *name, long line, const struct csv_line *r,
		      const int *idx, struct stray_sweep_entry *e,
		      struct stray_error *err)
{
	double seq;
	size_t i;
	int rc;

	if ((rc = check_file(name, line, r->f[idx[COL_FILE]], err)) ||
	    (rc = check_sha(name, line, r->f[idx[COL_SHA]], err)))
		return rc;
	strcpy(e->file, r->f[idx[COL_FILE]]);
	for (i = 0; i < 65; i++)
		e->sha256[i] = (char)tolower((unsigned char)r->f[idx[COL_SHA]][i]);
	e->type = stray_sweep_frametyp_parse(r->f[idx[COL_TYPE]]);
	if (e->type < 0)
		return bad_cell(name, line, columns[COL_TYPE],
				"must be DARK, AMBIENT or FULL",
				r->f[idx[COL_TYPE]], err);
	if ((rc = number(name, line, columns[COL_ANGLE], r->f[idx[COL_ANGLE]],
			 &e->angle_deg, err)) ||
	    (rc = number(name, line, columns[COL_EXP], r->f[idx[COL_EXP]],
			 &e->exptime_s, err)) ||
	    (rc = number(name, line, columns[COL_ND], r->f[idx[COL_ND]],
			 &e->ndtrans, err)) ||
	    (rc = number(name, line, columns[COL_SEQ], r->f[idx[COL_SEQ]], &seq,
			 err)))
		return rc;
	if (fabs(e->angle_deg) > 180.0)
		return bad_cell(name, line, columns[COL_ANGLE],
				"must be within -180..180", r->f[idx[COL_ANGLE]],
				err);
	if (!(e->exptime_s > 0.0))
		return bad_cell(name, line, columns[COL_EXP], "must be > 0",
				r->f[idx[COL_EXP]], err);
	if (!(e->ndtrans > 0.0 && e->ndtrans <= 1.0))
		return bad_cell(name, line, columns[COL_ND],
				"must be in (0, 1]",
				r->f[idx[COL_ND]], err);
	if (seq < 0 || seq > 1e9 || seq != floor(seq))
		return bad_cell(name, line, columns[COL_SEQ],
				"must be a whole number >= 0", r->f[idx[COL_SEQ]],
				err);
	e->seqnum = (long)seq;
	e->line = line;
	e->date_obs = NAN;
	if (idx[COL_DATE] >= 0 && (size_t)idx[COL_DATE] < r->n &&
	    r->f[idx[COL_DATE]][0] &&
	    stray_sweep_utc_parse(r->f[idx[COL_DATE]], &e->date_obs) !=
	    STRAY_OK)
		return bad_cell(name, line, STRAY_SWEEP_COL_DATE_OBS,
				"must be a UTC time like "
				"2026-12-02T04:50:00.123Z",
				r->f[idx[COL_DATE]], err);
	return STRAY_OK;
}

static int take_header(const char *name, long line, const struct csv_line *r,
		       int *idx, struct stray_error *err)
{
	size_t c, k;

	for (c = 0; c < N_COLS; c++) {
		idx[c] = -1;
		for (k = 0; k < r->n; k++)
			if (strcmp(r->f[k], columns[c]) == 0)
				idx[c] = (int)k;
		if (idx[c] < 0)
			return stray_error_at(err, STRAY_ENOTFOUND, name, line,
					      columns[c],
					      "column missing from the header");
	}
	/* A folder written before frames had a time has no date_obs. */
	idx[COL_DATE] = -1;
	for (k = 0; k < r->n; k++)
		if (strcmp(r->f[k], STRAY_SWEEP_COL_DATE_OBS) == 0)
			idx[COL_DATE] = (int)k;
	return STRAY_OK;
}

static int push(struct stray_sweep_manifest *m, size_t *cap, const char *name,
		long line, struct stray_error *err)
{
	if (m->n == *cap) {
		size_t nc = *cap ? 2 * *cap : 64;
		struct stray_sweep_entry *e = realloc(m->e, nc * sizeof(*e));

		if (!e)
			return stray_error_at(err, STRAY_ENOMEM, name, line, 0,
					      0);
		m->e = e;
		*cap = nc;
	}
	return STRAY_OK;
}

/* One line: blank, comment, header or entry. */
static int take_line(const char *name, long line, const char *s, size_t len,
		     struct stray_sweep_manifest *m, int *idx, int *have_header,
		     size_t *cap, struct csv_line *r, struct stray_error *err)
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
	if (r->n < N_COLS)
		return stray_error_at(err, STRAY_EPARSE, name, line, "row",
				      "fewer cells than the header");
	if ((rc = push(m, cap, name, line, err)) != STRAY_OK)
		return rc;
	rc = take_entry(name, line, r, idx, &m->e[m->n], err);
	if (rc == STRAY_OK)
		m->n++;
	return rc;
}

/* A frame listed twice would be counted twice: named with the line of
 * its second row (every reader of the folder sees it here). */
static int no_duplicates(const char *name, const struct stray_sweep_manifest *m,
			 struct stray_error *err)
{
	size_t dup;

	if (stray_sweep_repeated_file(m->e, m->n, sizeof(*m->e),
			offsetof(struct stray_sweep_entry, file),
			offsetof(struct stray_sweep_entry, line), &dup))
		return stray_error_at(err, STRAY_ENOMEM, name, 0, 0, 0);
	if (dup < m->n)
		return bad_cell(name, m->e[dup].line, columns[COL_FILE],
				"is listed twice (duplicate row)",
				m->e[dup].file, err);
	return STRAY_OK;
}

/*
 * The parser behind stray_sweep_manifest_parse; with allow_empty a
 * manifest of only its header is accepted (a writer resuming a sweep
 * that has no frame yet).
 */
int stray_sweep_manifest_parse_text(const char *name, const char *text,
				    size_t len, int allow_empty,
				    struct stray_sweep_manifest *m,
				    struct stray_error *err)
{
	struct csv_line *r = malloc(sizeof(*r));
	int idx[N_COLS + 1], have_header = 0, rc = STRAY_OK;
	size_t pos = 0, cap = 0;
	long line = 0;

	m->n = m->cap = 0;
	m->e = NULL;
	m->writer = 0;
	m->lock_fd = -1;
	if (!r)
		return stray_error_at(err, STRAY_ENOMEM, name, 0, 0, 0);
	while (pos < len && rc == STRAY_OK) {
		const char *nl = memchr(text + pos, '\n', len - pos);
		size_t end = nl ? (size_t)(nl - text) : len;

		rc = take_line(name, ++line, text + pos, end - pos, m, idx,
			       &have_header, &cap, r, err);
		pos = end + 1;
	}
	free(r);
	m->cap = cap;
	m->has_date = have_header && idx[COL_DATE] >= 0;
	if (rc == STRAY_OK && m->n == 0 && !(allow_empty && have_header))
		rc = stray_error_at(err, STRAY_EPARSE, name, line ? line : 1,
				    columns[COL_FILE],
				    "manifest lists no frames");
	if (rc == STRAY_OK)
		rc = no_duplicates(name, m, err);
	if (rc != STRAY_OK)
		stray_sweep_manifest_free(m);
	return rc;
}

int stray_sweep_manifest_parse(const char *name, const char *text,
			       size_t len, struct stray_sweep_manifest *m,
			       struct stray_error *err)
{
	m->dir[0] = '\0';
	return stray_sweep_manifest_parse_text(name, text, len, 0, m, err);
}

int stray_sweep_manifest_load(const char *dir,
			      struct stray_sweep_manifest *m,
			      struct stray_error *err)
{
	char path[STRAY_SWEEP_DIR_MAX + 16];
	char *text = NULL;
	size_t len = 0;
	int rc;

	m->n = m->cap = 0;
	m->e = NULL;
	m->writer = 0;
	m->lock_fd = -1;
	if (strlen(dir) >= sizeof(m->dir))
		return stray_error_at(err, STRAY_EINVAL, dir, 0, "dir",
				      "path too long");
	strcpy(m->dir, dir);
	snprintf(path, sizeof(path), "%s/" STRAY_SWEEP_MANIFEST, dir);
	if ((rc = stray_file_read(path, &text, &len, err)) != STRAY_OK)
		return rc;
	rc = stray_sweep_manifest_parse_text(path, text, len, 0, m, err);
	free(text);
	if (rc == STRAY_OK)
		rc = stray_sweep_manifest_check_files(path, m, err);
	if (rc != STRAY_OK)
		stray_sweep_manifest_free(m);
	return rc;
}

/* lstat, not stat: a symlink is refused, whatever it points at. */
int stray_sweep_manifest_check_files(const char *path,
				     const struct stray_sweep_manifest *m,
				     struct stray_error *err)
{
	char file[STRAY_SWEEP_DIR_MAX + STRAY_SWEEP_FILE_MAX + 2];
	struct stat st;
	size_t i;

	for (i = 0; i < m->n; i++) {
		snprintf(file, sizeof(file), "%s/%s", m->dir, m->e[i].file);
		if (lstat(file, &st) == 0 && !S_ISREG(st.st_mode))
			return bad_cell(path, m->e[i].line, columns[COL_FILE],
				S_ISLNK(st.st_mode)
				? "is a symbolic link: frames must be plain "
				  "files in the sweep folder"
				: "is not a regular file (a FIFO, device or "
				  "folder)", m->e[i].file, err);
	}
	return STRAY_OK;
}

void stray_sweep_manifest_free(struct stray_sweep_manifest *m)
{
	free(m->e);
	m->e = NULL;
	m->n = m->cap = 0;
	if (m->writer)
		close(m->lock_fd);	/* releases the flock */
	m->writer = 0;
	m->lock_fd = -1;
}

int stray_sweep_manifest_count(const struct stray_sweep_manifest *m,
			       double angle_deg, int type,
			       const struct stray_sweep_entry **first)
{
	size_t i;
	int n = 0;

	if (first)
		*first = NULL;
	for (i = 0; i < m->n; i++) {
		const struct stray_sweep_entry *e = &m->e[i];

		if (e->type != type || fabs(e->angle_deg - angle_deg) > 1e-6)
			continue;
		if (first && !*first)
			*first = e;
		n++;
	}
	return n;
}
