/*
 * store.c - the writer of a sweep folder (sweep_store.h): manifest.csv
 * created with its header and locked (one writer per folder), one
 * fsynced line appended per frame after its FITS file is in place, and
 * on resume read back, its torn tail cut and every row's file checked
 * against its SHA-256 before the sweep continues.
 */
#define _DEFAULT_SOURCE	/* DT_REG in dirent, flock */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sweep_store.h"
#include "sweep_priv.h"

#define HEADER STRAY_SWEEP_MANIFEST_HEADER

static void manifest_path(const struct stray_sweep_manifest *m, char *out,
			  size_t size)
{
	snprintf(out, size, "%s/" STRAY_SWEEP_MANIFEST, m->dir);
}

/* Cut a torn last line (a crash inside the append) off the file. */
static int cut_torn_tail(const char *path, size_t *len,
			 const char *text)
{
	size_t n = *len;

	while (n > 0 && text[n - 1] != '\n')
		n--;
	if (n == *len)
		return STRAY_OK;
	*len = n;
	return truncate(path, (off_t)n) == 0 ? STRAY_OK : STRAY_EIO;
}

static int load(struct stray_sweep_manifest *m, const char *path,
		struct stray_error *err)
{
	char dir[STRAY_SWEEP_DIR_MAX];
	char *text = NULL;
	size_t len = 0;
	int rc, fd = m->lock_fd, writer = m->writer;

	if ((rc = stray_file_read(path, &text, &len, err)) != STRAY_OK)
		return rc;
	if (cut_torn_tail(path, &len, text) != STRAY_OK) {
		free(text);
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      "cannot cut the torn last line");
	}
	strcpy(dir, m->dir);
	rc = stray_sweep_manifest_parse_text(path, text, len, 1, m, err);
	free(text);
	strcpy(m->dir, dir);
	m->lock_fd = fd;	/* the parser reset them: keep the lock */
	m->writer = writer;
	if (rc == STRAY_OK)
		rc = stray_sweep_manifest_check_files(path, m, err);
	return rc;
}

static int verify_rows(const struct stray_sweep_manifest *m,
		       struct stray_error *err)
{
	char path[STRAY_SWEEP_DIR_MAX + STRAY_SWEEP_FILE_MAX + 2];
	size_t i;
	int rc;

	for (i = 0; i < m->n; i++) {
		snprintf(path, sizeof(path), "%s/%s", m->dir, m->e[i].file);
		rc = stray_sweep_sha256_check(path, m->e[i].sha256, err);
		if (rc != STRAY_OK)
			return rc;
	}
	return STRAY_OK;
}

static int listed(const struct stray_sweep_manifest *m, const char *name)
{
	size_t i;

	for (i = 0; i < m->n; i++)
		if (strcmp(m->e[i].file, name) == 0)
			return 1;
	return 0;
}

/* Remove temporaries and frame files that no manifest row names. */
static void remove_orphans(const struct stray_sweep_manifest *m)
{
	DIR *d = opendir(m->dir);
	struct dirent *e;
	char path[STRAY_SWEEP_DIR_MAX + 260];

	while (d && (e = readdir(d)) != NULL) {
		size_t n = strlen(e->d_name);
		int tmp = n > 4 && strcmp(e->d_name + n - 4, ".tmp") == 0;
		int fits = n > 5 && strcmp(e->d_name + n - 5, ".fits") == 0;

		if ((tmp || (fits && !listed(m, e->d_name))) &&
		    e->d_name[0] == 'a') {
			snprintf(path, sizeof(path), "%s/%s", m->dir,
				 e->d_name);
			unlink(path);
		}
	}
	if (d)
		closedir(d);
}

/* Take the folder's lock on the open manifest fd; refused if held. */
static int lock(struct stray_sweep_manifest *m, int fd, const char *path,
		struct stray_error *err)
{
	m->lock_fd = fd;
	m->writer = 1;		/* closed by stray_sweep_manifest_free */
	if (flock(fd, LOCK_EX | LOCK_NB) == 0)
		return STRAY_OK;
	return stray_error_at(err, STRAY_EIO, path, 0, "file",
			      errno == EWOULDBLOCK
			      ? "sweep folder is in use by another writer"
			      : "cannot lock the sweep folder");
}

static int write_header(int fd, const char *path, struct stray_error *err)
{
	if (write(fd, HEADER, strlen(HEADER)) != (ssize_t)strlen(HEADER) ||
	    fsync(fd) != 0)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      "cannot write the manifest header");
	return STRAY_OK;
}

/* An I/O failure with its cause: errno's text as the value, what to do
 * in the reason ("F: dir 'Permission denied': cannot create ..."). */
static int with_cause(struct stray_error *err, const char *path,
		      const char *field, const char *reason)
{
	int e = errno;

	stray_error_at(err, STRAY_EIO, path, 0, field, reason);
	stray_error_text(err, strerror(e));
	return STRAY_EIO;
}

static int create(struct stray_sweep_manifest *m, const char *path,
		  struct stray_error *err)
{
	int fd, rc;

	if (mkdir(m->dir, 0755) != 0 && errno != EEXIST)
		return with_cause(err, m->dir, "dir", "cannot create the sweep "
				  "folder; check that its parent exists and "
				  "is writable, or choose another");
	fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
	if (fd < 0 && errno == EEXIST)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
			"exists; resume the sweep or use a new folder");
	if (fd < 0)
		return with_cause(err, path, "file", "cannot create the "
				  "manifest; check the folder is writable");
	rc = lock(m, fd, path, err);
	m->has_date = 1;
	return rc == STRAY_OK ? write_header(fd, path, err) : rc;
}

/* Resume: lock the manifest, then read, check and tidy the folder.  A
 * kill before the header was written leaves an empty manifest: resuming
 * that is starting afresh. */
static int resume_open(struct stray_sweep_manifest *m, const char *path,
		       struct stray_error *err)
{
	struct stat st;
	int fd = open(path, O_RDWR), rc;

	if (fd < 0)
		return stray_error_at(err, STRAY_EIO, path, 0, "file",
				      "cannot open");
	if ((rc = lock(m, fd, path, err)) != STRAY_OK)
		return rc;
	if (fstat(fd, &st) == 0 && st.st_size == 0) {
		m->has_date = 1;
		return write_header(fd, path, err);
	}
	rc = load(m, path, err);
	if (rc == STRAY_OK)
		rc = verify_rows(m, err);
	if (rc == STRAY_OK)
		remove_orphans(m);
	return rc;
}

int stray_sweep_store_open(struct stray_sweep_manifest *m, const char *dir,
			   int resume, struct stray_error *err)
{
	char path[STRAY_SWEEP_DIR_MAX + 16];
	int rc;

	memset(m, 0, sizeof(*m));
	m->lock_fd = -1;
	if (strlen(dir) >= sizeof(m->dir))
		return stray_error_at(err, STRAY_EINVAL, dir, 0, "dir",
				      "path too long");
	strcpy(m->dir, dir);
	manifest_path(m, path, sizeof(path));
	if (!resume || access(path, F_OK) != 0)
		rc = create(m, path, err);
	else
		rc = resume_open(m, path, err);
	if (rc != STRAY_OK)
		stray_sweep_manifest_free(m);
	return rc;
}

static int grow(struct stray_sweep_manifest *m)
{
	struct stray_sweep_entry *p;
	size_t cap = m->cap ? 2 * m->cap : 64;

	if (m->n < m->cap)
		return STRAY_OK;
	p = realloc(m->e, cap * sizeof(*p));
	if (!p)
		return STRAY_ENOMEM;
	m->e = p;
	m->cap = cap;
	return STRAY_OK;
}

/* One write() per row: a crash leaves at most one torn tail. */
static int append_row(struct stray_sweep_manifest *m,
		      const struct stray_sweep_entry *e,
		      struct stray_error *err)
{
	char path[STRAY_SWEEP_DIR_MAX + 16], line[512];
	char date[STRAY_SWEEP_UTC_LEN] = "";
	int fd, n;

	/* A folder begun before manifests had a time keeps its columns. */
	if (m->has_date && e->date_obs > 0)
		stray_sweep_utc_format(e->date_obs, date, sizeof(date));
	manifest_path(m, path, sizeof(path));
	n = snprintf(line, sizeof(line), "%s,%s,%.4f,%.6f,%.6g,%ld,%s%s%s\n",
		     e->file, stray_sweep_frametyp_name(e->type),
		     e->angle_deg, e->exptime_s, e->ndtrans, e->seqnum,
		     e->sha256, m->has_date ? "," : "", date);
	fd = open(path, O_WRONLY | O_APPEND);
	if (fd < 0 || n >= (int)sizeof(line) ||
	    write(fd, line, (size_t)n) != n || fsync(fd) != 0) {
		int e = errno;

		if (fd >= 0)
			close(fd);
		errno = e;
		return with_cause(err, path, "file", "cannot append the "
				  "frame's row; free space (or fix the "
				  "folder), then resume");
	}
	close(fd);
	return STRAY_OK;
}

int stray_sweep_store_append(struct stray_sweep_manifest *m,
			     const struct stray_sweep_frame *f,
			     const struct stray_sweep_image *img,
			     struct stray_error *err)
{
	struct stray_sweep_entry e;
	int rc;

	memset(&e, 0, sizeof(e));
	if (grow(m) != STRAY_OK)
		return stray_error_at(err, STRAY_ENOMEM, m->dir, 0, "file",
				      "no memory for the manifest");
	stray_sweep_frame_filename(f, e.file, sizeof(e.file));
	e.type = f->type;
	e.angle_deg = f->angle_deg;
	e.exptime_s = f->exptime_s;
	e.ndtrans = f->ndtrans;
	e.seqnum = f->seqnum;
	e.date_obs = f->date_obs > 0 ? f->date_obs : NAN;
	e.line = (long)m->n + 2;	/* after the header */
	rc = stray_sweep_fits_write(m->dir, e.file, img, f, e.sha256, err);
	if (rc == STRAY_OK)
		rc = append_row(m, &e, err);
	if (rc == STRAY_OK)
		m->e[m->n++] = e;
	return rc;
}
