/*
 * fits_write.c - one lab frame as a FITS file with cfitsio (sweep_store.h):
 * primary HDU, 16-bit unsigned (BITPIX 16, BZERO 32768, which cfitsio
 * writes for USHORT_IMG), keywords of docs/formats.md.  Written to a
 * temporary, fsynced and renamed, so a crash never leaves half a frame
 * under the real name.
 */
#include <errno.h>
#include <fcntl.h>
#include <fitsio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "stray/errfmt.h"
#include "stray/provenance.h"
#include "stray/sweep_store.h"
#include "sweep_priv.h"

static void rows_keyword(const struct stray_sweep_image *img, char *out,
			 size_t size)
{
	size_t n = 0, r;

	out[0] = '\0';
	for (r = 0; r < img->n_rows && n < size; r++)
		n += (size_t)snprintf(out + n, size - n, "%s%u", r ? "," : "",
				      img->rows[r]);
}

/* The writer's own keywords, after the lab-frame ones. */
static void write_extra(fitsfile *f, const struct stray_sweep_frame *m,
			int *status)
{
	size_t i;

	for (i = 0; i < m->n_extra; i++) {
		const struct stray_sweep_key *k = &m->extra[i];

		if (k->kind == STRAY_SWEEP_KEY_DOUBLE)
			fits_write_key(f, TDOUBLE, k->key, (void *)&k->d,
				       k->comment, status);
		else if (k->kind == STRAY_SWEEP_KEY_LONG)
			fits_write_key(f, TLONG, k->key, (void *)&k->l,
				       k->comment, status);
		else
			fits_write_key(f, TSTRING, k->key,
				       (void *)(k->s ? k->s : ""), k->comment,
				       status);
	}
}

static int write_keys(fitsfile *f, const struct stray_sweep_image *img,
		      const struct stray_sweep_frame *m, char *rows,
		      size_t rows_size, int *status)
{
	char type[16];
	double angle = m->angle_deg, t = m->exptime_s, nd = m->ndtrans;
	int seq = (int)m->seqnum, col0 = (int)img->col0, row0 = img->rows[0];
	int sat = (int)m->sat_dn;

	snprintf(type, sizeof(type), "%s",
		 stray_sweep_frametyp_name(m->type));
	fits_write_key(f, TSTRING, STRAY_SWEEP_KEY_FRAMETYP, type,
		       "DARK, AMBIENT (beam blocked) or FULL", status);
	fits_write_key(f, TDOUBLE, STRAY_SWEEP_KEY_ANGLE, &angle,
		       "[deg] boresight offset from the beam", status);
	fits_write_key(f, TDOUBLE, STRAY_SWEEP_KEY_EXPTIME, &t,
		       "[s] exposure time", status);
	fits_write_key(f, TDOUBLE, STRAY_SWEEP_KEY_NDTRANS, &nd,
		       "transmission of the ND filters in the beam", status);
	fits_write_key(f, TINT, STRAY_SWEEP_KEY_SEQNUM, &seq,
		       "index within its (angle, type) group", status);
	if (!m->full_frame) {
		rows_keyword(img, rows, rows_size);
		fits_write_key_longstr(f, STRAY_SWEEP_KEY_ROWS, rows,
				       "detector rows of the stored rows",
				       status);
	}
	fits_write_key(f, TINT, STRAY_SWEEP_KEY_COL0, &col0,
		       "detector column of the first pixel", status);
	fits_write_key(f, TINT, STRAY_SWEEP_KEY_ROW0, &row0,
		       "detector row of the first pixel", status);
	fits_write_key(f, TINT, STRAY_SWEEP_KEY_SATLEVEL, &sat,
		       "[DN] counts at which a pixel saturates", status);
	if (m->has_monitor)
		fits_write_key(f, TDOUBLE, STRAY_SWEEP_KEY_MONITOR,
			       (void *)&m->monitor,
			       "lamp level from the monitor, 1 = nominal",
			       status);
	if (m->instrument)
		fits_write_key(f, TSTRING, "INSTRUME", (void *)m->instrument,
			       "written by the straylight toolkit", status);
	else
		fits_write_key(f, TSTRING, "INSTRUME",
			       STRAY_SWEEP_INSTRUME_RIG,
			       "written by the straylight lab daemon", status);
	if (m->date_obs > 0) {
		char t0[STRAY_SWEEP_UTC_LEN], t1[STRAY_SWEEP_UTC_LEN];

		stray_sweep_utc_format(m->date_obs, t0, sizeof(t0));
		stray_sweep_utc_format(m->date_end > m->date_obs ? m->date_end
				       : m->date_obs, t1, sizeof(t1));
		t0[strlen(t0) - 1] = t1[strlen(t1) - 1] = '\0';	/* no Z */
		fits_write_key(f, TSTRING, "TIMESYS", "UTC",
			       "time scale of DATE-OBS and DATE-END", status);
		fits_write_key(f, TSTRING, STRAY_SWEEP_KEY_DATE_OBS, t0,
			       "start of the exposure", status);
		fits_write_key(f, TSTRING, STRAY_SWEEP_KEY_DATE_END, t1,
			       "end of the exposure (frame read)", status);
	}
	write_extra(f, m, status);
	stray_sweep_fits_provenance(f, status);
	return *status;
}

void stray_sweep_fits_provenance(void *fptr, int *status)
{
	char creator[96];
	const char *cmd = stray_provenance_command();

	snprintf(creator, sizeof(creator), "stray %s",
		 stray_provenance_version());
	fits_write_key((fitsfile *)fptr, TSTRING, "CREATOR", creator,
		       "program that wrote this file", status);
	if (cmd[0]) {	/* HISTORY cards, continued as cfitsio splits them */
		char line[4200];

		snprintf(line, sizeof(line), "command: %s", cmd);
		fits_write_history((fitsfile *)fptr, line, status);
	}
}

/* The frame as FITS bytes in a malloc'd *buf (*len of them): built in
 * memory, so cfitsio never sees a path (its "(", "[" and "!" syntax). */
static int build(const struct stray_sweep_image *img,
		 const struct stray_sweep_frame *m, void **buf, size_t *len,
		 int *status)
{
	long naxes[2] = { (long)img->n_cols, (long)img->n_rows };
	size_t rows_size = img->n_rows * 6 + 1, size = 2880;
	char *rows = malloc(rows_size);
	LONGLONG head = 0, data = 0, end = 0;
	fitsfile *f = NULL;

	*buf = malloc(size);
	if (!rows || !*buf) {
		free(rows);
		return *status = MEMORY_ALLOCATION;
	}
	fits_create_memfile(&f, buf, &size, 0, realloc, status);
	fits_create_img(f, USHORT_IMG, 2, naxes, status);
	write_keys(f, img, m, rows, rows_size, status);
	fits_write_img(f, TUSHORT, 1, (LONGLONG)img->n_rows * img->n_cols,
		       (void *)img->px, status);
	fits_get_hduaddrll(f, &head, &data, &end, status);	/* the length */
	free(rows);
	if (f) {
		int st2 = 0;

		fits_close_file(f, *status ? &st2 : status);
	}
	if (!*status && (end <= 0 || (size_t)end > size))
		*status = WRITE_ERROR;
	*len = (size_t)end;
	return *status;
}

static int sync_path(const char *path, int flags)
{
	int fd = open(path, flags), rc;

	if (fd < 0)
		return -1;
	rc = fsync(fd);
	close(fd);
	return rc;
}

/* len bytes to a new file tmp (a stale one replaced, no symlink
 * followed), fsynced. */
static int write_tmp(const char *tmp, const void *buf, size_t len)
{
	const char *p = buf;
	int fd, ok;

	unlink(tmp);
	fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
	if (fd < 0)
		return -1;
	for (ok = 1; ok && len > 0;) {
		ssize_t n = write(fd, p, len);

		if (n < 0 && errno == EINTR)
			continue;
		ok = n > 0;
		if (ok) {
			p += n;
			len -= (size_t)n;
		}
	}
	ok = ok && fsync(fd) == 0;
	return close(fd) == 0 && ok ? 0 : -1;
}

int stray_sweep_fits_write(const char *dir, const char *name,
		      const struct stray_sweep_image *img,
		      const struct stray_sweep_frame *m,
		      char sha_hex[STRAY_SWEEP_SHA256_HEX],
		      struct stray_error *err)
{
	char path[STRAY_SWEEP_DIR_MAX + STRAY_SWEEP_FILE_MAX + 2];
	char tmp[sizeof(path) + 4];
	void *buf = NULL;
	size_t len = 0;
	int status = 0, rc;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	snprintf(tmp, sizeof(tmp), "%s.tmp", path);
	if (build(img, m, &buf, &len, &status)) {
		char text[FLEN_STATUS];

		free(buf);
		fits_get_errstatus(status, text);
		fits_clear_errmsg();
		stray_error_at(err, STRAY_EIO, path, 0, "file",
			       "cfitsio cannot write the frame");
		stray_error_text(err, text);
		return STRAY_EIO;
	}
	if (write_tmp(tmp, buf, len) != 0 || rename(tmp, path) != 0 ||
	    sync_path(dir, O_RDONLY | O_DIRECTORY) != 0) {
		int e = errno;	/* the cause: a full disk, a read-only one */

		unlink(tmp);
		free(buf);
		stray_error_at(err, STRAY_EIO, path, 0, "file",
			       "cannot write, sync or rename the frame; "
			       "free space (or fix the folder), then resume");
		stray_error_text(err, strerror(e));
		return STRAY_EIO;
	}
	rc = stray_sweep_sha256_mem(buf, len, sha_hex);
	free(buf);
	return rc == STRAY_OK ? STRAY_OK
		: stray_error_at(err, STRAY_EIO, path, 0, "file",
				 "cannot hash the frame");
}
