/*
 * fits_frame.c - one lab frame as a FITS file with cfitsio: primary HDU,
 * 16-bit unsigned (BITPIX 16, BZERO 32768, which cfitsio writes for
 * USHORT_IMG), keywords of docs/formats.md.  Written to a temporary,
 * fsynced and renamed, so a crash never leaves half a frame under the
 * real name.
 */
#include <fcntl.h>
#include <fitsio.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "rig/store.h"

static const char *const type_names[RIG_FRAMETYP_COUNT] = {
	"DARK", "AMBIENT", "FULL"
};

const char *rig_frametyp_name(int type)
{
	return type >= 0 && type < RIG_FRAMETYP_COUNT ? type_names[type] : "?";
}

void rig_frame_filename(const struct rig_frame_meta *m, char *out,
			size_t size)
{
	snprintf(out, size, "a%+08.3f_%s_%03d.fits", m->angle_deg,
		 rig_frametyp_name(m->type), m->seqnum);
}

static void rows_keyword(const struct rig_image *img, char *out, size_t size)
{
	size_t n = 0;
	int r;

	out[0] = '\0';
	for (r = 0; r < img->n_rows && n < size; r++)
		n += (size_t)snprintf(out + n, size - n, "%s%u", r ? "," : "",
				      img->rows[r]);
}

static int write_keys(fitsfile *f, const struct rig_image *img,
		      const struct rig_frame_meta *m, int *status)
{
	char rows[RIG_FL_CMD_ROWS_MAX * 6 + 1];
	char type[16];
	double angle = m->angle_deg, t = m->exptime_s, nd = m->ndtrans;
	int seq = m->seqnum, col0 = img->col0, row0 = img->rows[0];
	int sat = m->sat_dn;

	snprintf(type, sizeof(type), "%s", rig_frametyp_name(m->type));
	fits_write_key(f, TSTRING, "FRAMETYP", type,
		       "DARK, AMBIENT (beam blocked) or FULL", status);
	fits_write_key(f, TDOUBLE, "ANGLE", &angle,
		       "[deg] boresight offset from the beam", status);
	fits_write_key(f, TDOUBLE, "EXPTIME", &t, "[s] exposure time",
		       status);
	fits_write_key(f, TDOUBLE, "NDTRANS", &nd,
		       "transmission of the ND filters in the beam", status);
	fits_write_key(f, TINT, "SEQNUM", &seq,
		       "index within its (angle, type) group", status);
	if (!m->full_frame) {
		rows_keyword(img, rows, sizeof(rows));
		fits_write_key_longstr(f, "ROWS", rows,
				       "detector rows of the stored rows",
				       status);
	}
	fits_write_key(f, TINT, "COL0", &col0,
		       "detector column of the first pixel", status);
	fits_write_key(f, TINT, "ROW0", &row0,
		       "detector row of the first pixel", status);
	fits_write_key(f, TINT, "SATLEVEL", &sat,
		       "[DN] counts at which a pixel saturates", status);
	if (m->has_monitor)
		fits_write_key(f, TDOUBLE, "MONITOR", (void *)&m->monitor,
			       "lamp level from the monitor, 1 = nominal",
			       status);
	fits_write_key(f, TSTRING, "INSTRUME", "strayrigd",
		       "written by the straylight lab daemon", status);
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

int rig_fits_write(const char *dir, const char *name,
		   const struct rig_image *img,
		   const struct rig_frame_meta *m,
		   char sha_hex[RIG_SHA256_HEX], struct rig_error *err)
{
	char path[1024], tmp[1100], ftmp[1110];
	long naxes[2] = { img->n_cols, img->n_rows };
	fitsfile *f = NULL;
	int status = 0;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	snprintf(tmp, sizeof(tmp), "%s.tmp", path);
	snprintf(ftmp, sizeof(ftmp), "!%s", tmp);	/* '!' = overwrite */
	fits_create_file(&f, ftmp, &status);
	fits_create_img(f, USHORT_IMG, 2, naxes, &status);
	write_keys(f, img, m, &status);
	fits_write_img(f, TUSHORT, 1, (LONGLONG)img->n_rows * img->n_cols,
		       img->px, &status);
	if (f) {
		int st2 = 0;

		fits_close_file(f, status ? &st2 : &status);
	}
	if (status) {
		char text[FLEN_STATUS];

		fits_get_errstatus(status, text);
		unlink(tmp);
		return rig_error_set(err, RIG_EIO, "%s: cfitsio: %s", path,
				     text);
	}
	if (sync_path(tmp, O_RDONLY) != 0 || rename(tmp, path) != 0 ||
	    sync_path(dir, O_RDONLY | O_DIRECTORY) != 0) {
		unlink(tmp);
		return rig_error_set(err, RIG_EIO, "%s: cannot sync or rename",
				     path);
	}
	return rig_sha256_file(path, sha_hex, err);
}
