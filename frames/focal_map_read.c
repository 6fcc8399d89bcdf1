/*
 * focal_map_read.c - a focal-plane stray-light map read back and
 * resampled to detector pixels (focal_map_io.h; the format is in
 * tracer/README.md).  The one reader of the file `stray trace
 * --focal-map` writes.
 */
#include <fitsio.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "frames/focal_map_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sizes.h"

/* One numeric keyword, NaN when the map does not carry it. */
static double read_key(fitsfile *fp, const char *key)
{
	double v = NAN;
	int st = 0;

	if (fits_read_key(fp, TDOUBLE, key, &v, NULL, &st) || !isfinite(v))
		v = NAN;
	fits_clear_errmsg();
	return v;
}

/* The keywords of `stray trace --focal-map`, where present. */
static int load_keys(fitsfile *fp, const char *path,
		     struct focal_map_file *m, struct stray_error *err)
{
	double cell = read_key(fp, "CELLPX");
	double nx = read_key(fp, "NPIXX"), ny = read_key(fp, "NPIXY");
	int st = 0;

	m->theta_deg = read_key(fp, "THETA");
	m->alpha = read_key(fp, "ALPHA");
	m->k_px = read_key(fp, "KPX");
	m->mean = read_key(fp, "MEAN");
	if (!isnan(cell)) {
		m->cell_px = (long)cell;
		m->npix_x = isnan(nx) ? -1 : (long)nx;
		m->npix_y = isnan(ny) ? -1 : (long)ny;
		if (m->cell_px < 1 || m->npix_x != m->nx * m->cell_px ||
		    m->npix_y != m->ny * m->cell_px)
			return stray_error_at(err, STRAY_EPARSE, path, 0,
					      "CELLPX",
					      "NAXIS * CELLPX must be NPIXX, NPIXY");
	}
	if (fits_read_key(fp, TSTRING, "SPREAD", m->spread, NULL, &st))
		snprintf(m->spread, sizeof(m->spread), "unknown");
	fits_clear_errmsg();
	return STRAY_OK;
}

/* Every cell finite and >= 0, some light: the cells' mean. */
static int check_cells(const char *path, struct focal_map_file *m,
		       struct stray_error *err)
{
	double sum = 0.0;
	long i;

	for (i = 0; i < m->nx * m->ny; i++) {
		if (!(isfinite(m->cell[i]) && m->cell[i] >= 0.0f))
			return stray_error_at(err, STRAY_EINVAL, path, 0, "pixel",
					      "map values must be finite and >= 0");
		sum += m->cell[i];
	}
	m->cell_mean = sum / ((double)m->nx * m->ny);
	if (!(m->cell_mean > 0.0))
		return stray_error_at(err, STRAY_EINVAL, path, 0, "MEAN",
				      "the map carries no light");
	return STRAY_OK;
}

/* NAXIS1 x NAXIS2 held to the bytes after the header and to the input
 * limit before the cells are allocated (a 6 KB file may claim 2^32 x
 * 2^30 cells, whose product wraps). */
static int check_size(fitsfile *fp, const char *path, off_t size,
		      const long naxes[2], struct stray_error *err)
{
	LONGLONG head = 0, data = 0, end = 0;
	size_t have = 0;
	int st = 0, bitpix = 0, rc;

	if (fits_get_img_type(fp, &bitpix, &st) ||
	    fits_get_hduaddrll(fp, &head, &data, &end, &st))
		return stray_error_at(err, STRAY_EPARSE, path, 0, "BITPIX",
				      "cannot be read");
	if (data >= 0 && (LONGLONG)size > data)
		have = (size_t)((LONGLONG)size - data);
	rc = stray_size_check2((size_t)naxes[0], (size_t)naxes[1],
			       sizeof(float), STRAY_FILE_READ_MAX, SIZE_MAX,
			       path, "NAXIS1 x NAXIS2", NULL, err);
	if (rc == STRAY_OK)
		rc = stray_size_check2((size_t)naxes[0], (size_t)naxes[1],
				       (size_t)(bitpix < 0 ? -bitpix : bitpix) / 8,
				       SIZE_MAX, have, path, "NAXIS1 x NAXIS2",
				       NULL, err);
	return rc;
}

/*
 * The map opened by its name as given (fits_open_diskfile: cfitsio's
 * "(", "[" and "!" syntax is not applied), a regular file only (a FIFO
 * would hang the open), its size checked.
 */
static int open_map(const char *path, fitsfile **fp, long naxes[2],
		    struct stray_error *err)
{
	char text[FLEN_STATUS] = "";
	struct stat sb;
	int st = 0, nax = 0, rc;

	if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
		return stray_error_at(err, STRAY_EINVAL, path, 0, 0,
				      S_ISDIR(sb.st_mode)
				      ? "is a directory, not a file"
				      : "is not a regular file");
	if (fits_open_diskfile(fp, path, READONLY, &st)) {
		fits_get_errstatus(st, text);
		fits_clear_errmsg();
		stray_error_at(err, STRAY_ENOTFOUND, path, 0, 0,
			       "cannot open the focal map");
		stray_error_text(err, text);
		return STRAY_ENOTFOUND;
	}
	stray_file_note_input(path);	/* no output of the run may replace it */
	if (fits_get_img_dim(*fp, &nax, &st) || nax != 2 ||
	    fits_get_img_size(*fp, 2, naxes, &st) || naxes[0] < 1 ||
	    naxes[1] < 1)
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "NAXIS",
				    "the map must be a 2-D image");
	else
		rc = check_size(*fp, path, sb.st_size, naxes, err);
	if (rc != STRAY_OK) {
		st = 0;
		fits_close_file(*fp, &st);
		fits_clear_errmsg();
	}
	return rc;
}

int focal_map_load(const char *path, struct focal_map_file *m,
		   struct stray_error *err)
{
	fitsfile *fp = NULL;
	long naxes[2] = { 0, 0 };
	int st = 0, rc;

	memset(m, 0, sizeof(*m));
	rc = open_map(path, &fp, naxes, err);
	if (rc)
		return rc;
	m->nx = naxes[0];
	m->ny = naxes[1];
	rc = load_keys(fp, path, m, err);
	if (!rc) {
		m->cell = malloc((size_t)m->nx * (size_t)m->ny * sizeof(float));
		if (!m->cell)
			rc = stray_error_at(err, STRAY_ENOMEM, path, 0, 0,
					    "no memory");
	}
	if (!rc && fits_read_img(fp, TFLOAT, 1, m->nx * m->ny, NULL, m->cell,
				 NULL, &st))
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "image",
				    "cannot read the focal map's cells");
	st = 0;
	fits_close_file(fp, &st);
	fits_clear_errmsg();
	if (!rc)
		rc = check_cells(path, m, err);
	if (rc)
		focal_map_file_free(m);
	return rc;
}

/* A detector pixel's position in map cells, measured between cell
 * centres. */
static double cell_coord(int px, int det, long n)
{
	return (px + 0.5) * (double)n / det - 0.5;
}

/* The cell left of (below) f, so that f lies in [i, i + 1] inside. */
static long cell_base(double f, long n)
{
	long i = (long)floor(f);

	return n < 2 ? 0 : i < 0 ? 0 : i > n - 2 ? n - 2 : i;
}

void focal_map_resample(const struct focal_map_file *m, int det_x,
			int det_y, int col0, int row0, int cols, int rows,
			double div, float *out)
{
	const float *img = m->cell;
	long nx = m->nx, ny = m->ny;
	int x, y;

	for (y = 0; y < rows; y++) {
		double fy = cell_coord(row0 + y, det_y, ny);
		long y0 = cell_base(fy, ny), y1 = ny > 1 ? y0 + 1 : y0;

		fy -= (double)y0;
		for (x = 0; x < cols; x++) {
			double fx = cell_coord(col0 + x, det_x, nx), top, bot, v;
			long x0 = cell_base(fx, nx), x1 = nx > 1 ? x0 + 1 : x0;

			fx -= (double)x0;
			top = img[y0 * nx + x0] + fx * (img[y0 * nx + x1] - img[y0 * nx + x0]);
			bot = img[y1 * nx + x0] + fx * (img[y1 * nx + x1] - img[y1 * nx + x0]);
			v = (top + fy * (bot - top)) / div;
			out[(size_t)y * cols + x] = (float)(v > 0.0 ? v : 0.0);
		}
	}
}

void focal_map_file_free(struct focal_map_file *m)
{
	free(m->cell);
	m->cell = NULL;
}
