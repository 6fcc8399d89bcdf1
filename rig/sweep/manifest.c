/*
 * manifest.c - manifest.csv of a sweep folder (store.h): created with its
 * header, appended one fsynced line per frame, and on resume read back
 * with libcsv, its torn tail cut and every row's file checked against its
 * SHA-256 before the sweep continues.
 */
#define _DEFAULT_SOURCE	/* DT_REG in dirent */
#include <csv.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rig/store.h"

#define MANIFEST "manifest.csv"
#define HEADER "file,frametyp,angle_deg,exptime_s,ndtrans,seqnum,sha256\n"
#define N_FIELDS 7

struct reader {
	struct rig_manifest *mf;
	char field[N_FIELDS][RIG_FILE_MAX + 8];
	int n_field;
	long line;
	int rc;
	struct rig_error *err;
};

static void on_field(void *s, size_t len, void *data)
{
	struct reader *r = data;

	if (r->n_field < N_FIELDS) {
		size_t n = len < RIG_FILE_MAX + 7 ? len : RIG_FILE_MAX + 7;

		memcpy(r->field[r->n_field], s, n);
		r->field[r->n_field][n] = '\0';
	}
	r->n_field++;
}

static int parse_type(const char *s)
{
	int t;

	for (t = 0; t < RIG_FRAMETYP_COUNT; t++)
		if (strcmp(s, rig_frametyp_name(t)) == 0)
			return t;
	return -1;
}

static int parse_num(const char *s, double *v)
{
	char *end;

	*v = strtod(s, &end);
	return *s && !*end && isfinite(*v);
}

static int grow(struct rig_manifest *mf)
{
	struct rig_manifest_row *p;
	size_t cap = mf->cap ? 2 * mf->cap : 64;

	if (mf->n < mf->cap)
		return RIG_OK;
	p = realloc(mf->rows, cap * sizeof(*p));
	if (!p)
		return RIG_ENOMEM;
	mf->rows = p;
	mf->cap = cap;
	return RIG_OK;
}

static int take_row(struct reader *r)
{
	struct rig_manifest_row row;
	double seq;

	memset(&row, 0, sizeof(row));
	if (r->n_field != N_FIELDS)
		return rig_error_set(r->err, RIG_EPARSE,
			"%s/" MANIFEST ":%ld: %d fields, expected 7",
			r->mf->dir, r->line, r->n_field);
	if (r->line == 1)
		return strcmp(r->field[0], "file") == 0 ? RIG_OK :
			rig_error_set(r->err, RIG_EPARSE,
				"%s/" MANIFEST ":1: header missing",
				r->mf->dir);
	row.meta.type = parse_type(r->field[1]);
	if (strlen(r->field[0]) >= RIG_FILE_MAX || strchr(r->field[0], '/') ||
	    row.meta.type < 0 || !parse_num(r->field[2], &row.meta.angle_deg) ||
	    !parse_num(r->field[3], &row.meta.exptime_s) ||
	    !parse_num(r->field[4], &row.meta.ndtrans) ||
	    !parse_num(r->field[5], &seq) || strlen(r->field[6]) != 64)
		return rig_error_set(r->err, RIG_EPARSE,
			"%s/" MANIFEST ":%ld: malformed row '%s'",
			r->mf->dir, r->line, r->field[0]);
	row.meta.seqnum = (int)seq;
	strcpy(row.file, r->field[0]);
	strcpy(row.sha256, r->field[6]);
	if (grow(r->mf) != RIG_OK)
		return rig_error_set(r->err, RIG_ENOMEM, "manifest: no memory");
	r->mf->rows[r->mf->n++] = row;
	return RIG_OK;
}

static void on_row(int c, void *data)
{
	struct reader *r = data;

	(void)c;
	r->line++;
	if (r->rc == RIG_OK)
		r->rc = take_row(r);
	r->n_field = 0;
}

/* Cut a torn last line (a crash inside the append) off the file. */
static int cut_torn_tail(const char *path, char *text, size_t *len)
{
	size_t n = *len;

	while (n > 0 && text[n - 1] != '\n')
		n--;
	if (n == *len)
		return RIG_OK;
	*len = n;
	return truncate(path, (off_t)n) == 0 ? RIG_OK : RIG_EIO;
}

static int read_all(const char *path, char **text, size_t *len)
{
	FILE *f = fopen(path, "rb");
	struct stat st;

	*text = NULL;
	if (!f)
		return RIG_EIO;
	if (fstat(fileno(f), &st) != 0 || !(*text = malloc(st.st_size + 1))) {
		fclose(f);
		return RIG_EIO;
	}
	*len = fread(*text, 1, (size_t)st.st_size, f);
	fclose(f);
	return RIG_OK;
}

static int load(struct rig_manifest *mf, const char *path,
		struct rig_error *err)
{
	struct reader r;
	struct csv_parser p;
	char *text;
	size_t len;

	memset(&r, 0, sizeof(r));
	r.mf = mf;
	r.err = err;
	if (read_all(path, &text, &len) != RIG_OK ||
	    cut_torn_tail(path, text, &len) != RIG_OK) {
		free(text);
		return rig_error_set(err, RIG_EIO, "%s: cannot read", path);
	}
	csv_init(&p, CSV_STRICT | CSV_APPEND_NULL);
	if (csv_parse(&p, text, len, on_field, on_row, &r) != len)
		r.rc = rig_error_set(err, RIG_EPARSE, "%s: %s", path,
				     csv_strerror(csv_error(&p)));
	csv_fini(&p, on_field, on_row, &r);
	csv_free(&p);
	free(text);
	if (r.rc == RIG_OK && r.line == 0)
		r.rc = rig_error_set(err, RIG_EPARSE, "%s: empty", path);
	return r.rc;
}

static int verify_rows(struct rig_manifest *mf, struct rig_error *err)
{
	char path[1024], hex[RIG_SHA256_HEX];
	size_t i;
	int rc;

	for (i = 0; i < mf->n; i++) {
		snprintf(path, sizeof(path), "%s/%s", mf->dir,
			 mf->rows[i].file);
		rc = rig_sha256_file(path, hex, err);
		if (rc != RIG_OK)
			return rc;
		if (strcmp(hex, mf->rows[i].sha256) != 0)
			return rig_error_set(err, RIG_EIO,
				"%s: sha256 differs from manifest.csv", path);
	}
	return RIG_OK;
}

static int listed(const struct rig_manifest *mf, const char *name)
{
	size_t i;

	for (i = 0; i < mf->n; i++)
		if (strcmp(mf->rows[i].file, name) == 0)
			return 1;
	return 0;
}

/* Remove temporaries and frame files that no manifest row names. */
static void remove_orphans(struct rig_manifest *mf)
{
	DIR *d = opendir(mf->dir);
	struct dirent *e;
	char path[1024];

	while (d && (e = readdir(d)) != NULL) {
		size_t n = strlen(e->d_name);
		int tmp = n > 4 && strcmp(e->d_name + n - 4, ".tmp") == 0;
		int fits = n > 5 && strcmp(e->d_name + n - 5, ".fits") == 0;

		if ((tmp || (fits && !listed(mf, e->d_name))) &&
		    e->d_name[0] == 'a') {
			snprintf(path, sizeof(path), "%s/%s", mf->dir,
				 e->d_name);
			unlink(path);
		}
	}
	if (d)
		closedir(d);
}

static int create(struct rig_manifest *mf, const char *path,
		  struct rig_error *err)
{
	int fd;

	if (mkdir(mf->dir, 0755) != 0 && errno != EEXIST)
		return rig_error_set(err, RIG_EIO, "%s: cannot create folder",
				     mf->dir);
	fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
	if (fd < 0)
		return rig_error_set(err, RIG_EIO, errno == EEXIST ?
			"%s: exists; resume the sweep or use a new folder" :
			"%s: cannot create", path);
	if (write(fd, HEADER, strlen(HEADER)) != (ssize_t)strlen(HEADER) ||
	    fsync(fd) != 0) {
		close(fd);
		return rig_error_set(err, RIG_EIO, "%s: cannot write", path);
	}
	close(fd);
	return RIG_OK;
}

static int is_empty(const char *path)
{
	struct stat st;

	return stat(path, &st) == 0 && st.st_size == 0;
}

int rig_manifest_open(struct rig_manifest *mf, const char *dir, int resume,
		      struct rig_error *err)
{
	char path[1024];
	int rc;

	memset(mf, 0, sizeof(*mf));
	if (strlen(dir) >= sizeof(mf->dir))
		return rig_error_set(err, RIG_EINVAL, "%s: path too long", dir);
	strcpy(mf->dir, dir);
	snprintf(path, sizeof(path), "%s/" MANIFEST, dir);
	/* A kill before the header was written leaves no or an empty
	 * manifest: resuming that is starting afresh. */
	if (!resume || access(path, F_OK) != 0)
		return create(mf, path, err);
	if (is_empty(path) && unlink(path) == 0)
		return create(mf, path, err);
	rc = load(mf, path, err);
	if (rc == RIG_OK)
		rc = verify_rows(mf, err);
	if (rc == RIG_OK)
		remove_orphans(mf);
	return rc;
}

int rig_manifest_append(struct rig_manifest *mf,
			const struct rig_manifest_row *row,
			struct rig_error *err)
{
	char path[1024], line[256];
	int fd, n;

	snprintf(path, sizeof(path), "%s/" MANIFEST, mf->dir);
	n = snprintf(line, sizeof(line), "%s,%s,%.4f,%.6f,%.6g,%d,%s\n",
		     row->file, rig_frametyp_name(row->meta.type),
		     row->meta.angle_deg, row->meta.exptime_s,
		     row->meta.ndtrans, row->meta.seqnum, row->sha256);
	fd = open(path, O_WRONLY | O_APPEND);
	/* One write() per row: a crash leaves at most one torn tail. */
	if (fd < 0 || write(fd, line, (size_t)n) != n || fsync(fd) != 0) {
		if (fd >= 0)
			close(fd);
		return rig_error_set(err, RIG_EIO, "%s: cannot append", path);
	}
	close(fd);
	if (grow(mf) != RIG_OK)
		return rig_error_set(err, RIG_ENOMEM, "manifest: no memory");
	mf->rows[mf->n++] = *row;
	return RIG_OK;
}

int rig_manifest_count(const struct rig_manifest *mf, double angle_deg,
		       int type, const struct rig_manifest_row **first)
{
	size_t i;
	int n = 0;

	if (first)
		*first = NULL;
	for (i = 0; i < mf->n; i++) {
		const struct rig_manifest_row *r = &mf->rows[i];

		if (r->meta.type != type || fabs(r->meta.angle_deg -
						 angle_deg) > 1e-6)
			continue;
		if (first && !*first)
			*first = r;
		n++;
	}
	return n;
}

void rig_manifest_close(struct rig_manifest *mf)
{
	free(mf->rows);
	mf->rows = NULL;
	mf->n = mf->cap = 0;
}
