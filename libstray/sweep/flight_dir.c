/*
 * flight_dir.c - a folder of flight frames without a manifest (issue
 * 24): the FITS files a tracker or camera wrote, listed as the rows of a
 * manifest with no hash (stray/sweep_store.h).
 */
#include <dirent.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sizes.h"
#include "stray/sweep_store.h"

static int fits_name(const char *n)
{
	size_t l = strlen(n);
	static const char *const ext[] = { ".fits", ".fit", ".fts", ".FITS",
					   ".FIT", ".FTS" };
	size_t k;

	if (n[0] == '.' || l >= STRAY_SWEEP_FILE_MAX)
		return 0;
	for (k = 0; k < sizeof(ext) / sizeof(ext[0]); k++) {
		size_t e = strlen(ext[k]);

		if (l > e && strcmp(n + l - e, ext[k]) == 0)
			return 1;
	}
	return 0;
}

static int by_name(const void *a, const void *b)
{
	return strcmp(((const struct stray_sweep_entry *)a)->file,
		      ((const struct stray_sweep_entry *)b)->file);
}

int stray_sweep_flight_list(const char *dir, struct stray_sweep_manifest *m,
			    struct stray_error *err)
{
	DIR *d;
	struct dirent *de;
	int rc = STRAY_OK;

	memset(m, 0, sizeof(*m));
	m->lock_fd = -1;
	if (strlen(dir) >= sizeof(m->dir))
		return stray_error_at(err, STRAY_EINVAL, dir, 0, "folder",
				      "path too long");
	snprintf(m->dir, sizeof(m->dir), "%s", dir);
	if (!(d = opendir(dir)))
		return stray_error_at(err, STRAY_ENOTFOUND, dir, 0, "folder",
				      "cannot be opened");
	while (rc == STRAY_OK && (de = readdir(d))) {
		struct stray_sweep_entry *e;

		if (!fits_name(de->d_name))
			continue;
		if (m->n == m->cap) {
			size_t cap = m->cap ? 2 * m->cap : 64;

			if (m->n >= STRAY_SWEEP_FLIGHT_FILES_MAX) {
				rc = stray_error_at(err, STRAY_EINVAL, dir, 0, "folder",
					"more than 100000 FITS files (docs/limits.md)");
				break;
			}
			e = realloc(m->e, cap * sizeof(*e));
			if (!e) {
				rc = stray_error_set(err, STRAY_ENOMEM, dir,
						     "out of memory");
				break;
			}
			m->e = e;
			m->cap = cap;
		}
		e = &m->e[m->n++];
		memset(e, 0, sizeof(*e));
		snprintf(e->file, sizeof(e->file), "%s", de->d_name);
		e->type = STRAY_SWEEP_FULL;
		e->ndtrans = 1.0;
	}
	closedir(d);
	if (rc == STRAY_OK && m->n == 0)
		rc = stray_error_at(err, STRAY_EINVAL, dir, 0, "folder",
				    "no manifest.csv and no .fits file");
	if (rc != STRAY_OK) {
		stray_sweep_manifest_free(m);
		return rc;
	}
	/* frames in name order (trackers number them) */
	qsort(m->e, m->n, sizeof(*m->e), by_name);
	return STRAY_OK;
}

int stray_sweep_flight_files(char *const *paths, size_t n,
			     struct stray_sweep_manifest *m,
			     struct stray_error *err)
{
	struct stat st;
	size_t i;

	memset(m, 0, sizeof(*m));
	m->lock_fd = -1;	/* m->dir "": each file is its own path */
	if (n == 0 || n > STRAY_SWEEP_FLIGHT_FILES_MAX)
		return stray_error_at(err, STRAY_EINVAL, "frames", 0, "files",
				      "1 to 100000 FITS files");
	if (!(m->e = calloc(n, sizeof(*m->e))))
		return stray_error_set(err, STRAY_ENOMEM, "frames",
				       "out of memory");
	m->cap = n;
	for (i = 0; i < n; i++) {
		struct stray_sweep_entry *e = &m->e[m->n++];

		if (strlen(paths[i]) >= sizeof(e->file)) {
			stray_sweep_manifest_free(m);
			return stray_error_at(err, STRAY_EINVAL, paths[i], 0,
					      "file", "path too long");
		}
		if (lstat(paths[i], &st) != 0) {
			stray_sweep_manifest_free(m);
			return stray_error_at(err, STRAY_ENOTFOUND, paths[i], 0,
					      "file", "no such file");
		}
		snprintf(e->file, sizeof(e->file), "%s", paths[i]);
		e->type = STRAY_SWEEP_FULL;
		e->ndtrans = 1.0;
	}
	return STRAY_OK;	/* in the order given */
}
