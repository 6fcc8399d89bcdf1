/*
 * import_frame.c - a frame written by other software (sweep_import.h):
 * FITS as INDI/EKOS, N.I.N.A., MaxIm or a camera SDK writes it, read
 * through cfitsio from memory, its keywords put in our terms; TIFF goes
 * to import_tiff.c.  Only 16-bit unsigned counts of one grey plane are
 * taken: anything else would have to be rescaled, and a rescaled count
 * is not what the camera measured.
 */
#include <errno.h>
#include <fitsio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "import_priv.h"
#include "stray/errfmt.h"
#include "stray/sizes.h"
#include "stray/sweep_import.h"

static const char *const setting_keys[STRAY_IMPORT_SETTINGS] = {
	"GAIN", "EGAIN", "OFFSET", "PEDESTAL", "CCD-TEMP"
};

const char *stray_import_setting_key(int k)
{
	return k >= 0 && k < STRAY_IMPORT_SETTINGS ? setting_keys[k] : "?";
}

static int fits_bad(const char *path, const char *key, const char *why,
		    int status, struct stray_error *err)
{
	char text[FLEN_STATUS] = "";

	if (status && status != KEY_NO_EXIST)
		fits_get_errstatus(status, text);
	fits_clear_errmsg();
	stray_error_at(err, status == KEY_NO_EXIST ? STRAY_ENOTFOUND
		       : STRAY_EPARSE, path, 0, key, why);
	stray_error_text(err, text);
	return err ? err->code : STRAY_EPARSE;
}

/* A keyword's raw value text; 0 absent, 1 present, -1 unreadable.  The
 * text is converted here, never by cfitsio's own numeric conversion
 * (fits_read.c: it aborts on some malformed values). */
static int key_text(fitsfile *f, const char *key, char *text)
{
	int status = 0;

	if (fits_read_keyword(f, key, text, NULL, &status) == 0)
		return 1;
	fits_clear_errmsg();
	return status == KEY_NO_EXIST ? 0 : -1;
}

/* A numeric keyword: 0 absent, 1 read into *v, else an error. */
static int key_num(fitsfile *f, const char *path, const char *key, double *v,
		   struct stray_error *err)
{
	char text[FLEN_VALUE], *end;
	int got = key_text(f, key, text);

	if (got == 0)
		return 0;
	errno = 0;
	*v = got > 0 ? strtod(text, &end) : NAN;
	if (got > 0)
		while (*end == ' ')
			end++;
	if (got < 0 || end == text || *end || errno || !isfinite(*v)) {
		stray_error_at(err, STRAY_EPARSE, path, 0, key,
			       "is not a finite number");
		stray_error_text(err, got > 0 ? text : "");
		return -1;
	}
	return 1;
}

/* A string keyword (quotes and trailing blanks gone): 0 absent, 1 read. */
static int key_str(fitsfile *f, const char *path, const char *key, char *out,
		   size_t size, struct stray_error *err)
{
	char text[FLEN_VALUE];
	int status = 0;

	out[0] = '\0';
	if (fits_read_key(f, TSTRING, key, text, NULL, &status)) {
		if (status == KEY_NO_EXIST) {
			fits_clear_errmsg();
			return 0;
		}
		fits_bad(path, key, "is not a string", status, err);
		return -1;
	}
	snprintf(out, size, "%s", text);
	return 1;
}

/* IMAGETYP (MaxIm, N.I.N.A., INDI 2) or FRAME (INDI): light or dark.
 * A bias or a flat has no place in a stray-light sweep. */
static int frame_kind(fitsfile *f, const char *path,
		      struct stray_import_header *h, struct stray_error *err)
{
	static const char *const lights[] = { "Light Frame", "Light", "LIGHT",
					      "Object", NULL };
	static const char *const darks[] = { "Dark Frame", "Dark", "DARK",
					     NULL };
	const char *key = "IMAGETYP";
	int got = key_str(f, path, key, h->imagetyp, sizeof(h->imagetyp),
			  err), k;

	if (got == 0) {
		key = "FRAME";
		got = key_str(f, path, key, h->imagetyp, sizeof(h->imagetyp),
			      err);
	}
	h->light = -1;
	if (got <= 0)
		return got < 0 ? -1 : 0;
	for (k = 0; lights[k]; k++)
		if (strcasecmp(h->imagetyp, lights[k]) == 0)
			h->light = 1;
	for (k = 0; darks[k]; k++)
		if (strcasecmp(h->imagetyp, darks[k]) == 0)
			h->light = 0;
	if (h->light >= 0)
		return 0;
	stray_error_at(err, STRAY_EINVAL, path, 0, key, strncasecmp(
		h->imagetyp, "Bias", 4) == 0 || strncasecmp(h->imagetyp,
		"Flat", 4) == 0 ? "a bias or flat frame has no place in a "
		"stray-light sweep (darks are taken at each exposure)" :
		"must be a light or a dark frame ('Light Frame', 'Dark "
		"Frame', or INDI's FRAME 'Light', 'Dark')");
	stray_error_text(err, h->imagetyp);
	return -1;
}

/* EXPTIME, else EXPOSURE; both present must agree. */
static int exposure(fitsfile *f, const char *path,
		    struct stray_import_header *h, struct stray_error *err)
{
	double e2;
	int a = key_num(f, path, "EXPTIME", &h->exptime_s, err), b;

	if (a < 0 || (b = key_num(f, path, "EXPOSURE", &e2, err)) < 0)
		return -1;
	if (a == 0 && b == 0)
		return stray_error_at(err, STRAY_ENOTFOUND, path, 0, "EXPTIME",
			"missing (nor EXPOSURE): a camera's frame says its "
			"exposure; the log alone cannot be checked"), -1;
	if (a == 0)
		h->exptime_s = e2;
	else if (b && fabs(e2 - h->exptime_s) > 1e-6 * fmax(1.0, e2)) {
		stray_error_at(err, STRAY_EINVAL, path, 0, "EXPOSURE",
			       "differs from EXPTIME in the same header");
		stray_error_text(err, "");
		return -1;
	}
	h->has_exptime = 1;
	if (!(h->exptime_s > 0.0))
		return stray_error_at(err, STRAY_EINVAL, path, 0, a ? "EXPTIME"
				      : "EXPOSURE", "must be > 0"), -1;
	return 0;
}

/* A whole number keyword within lo..hi: 0 absent, 1 read, -1 error. */
static int key_whole(fitsfile *f, const char *path, const char *key,
		     long lo, long hi, long *v, struct stray_error *err)
{
	double x;
	int got = key_num(f, path, key, &x, err);

	if (got <= 0)
		return got;
	if (x != floor(x) || x < (double)lo || x > (double)hi)
		return stray_error_at(err, STRAY_EINVAL, path, 0, key,
				      "is not a whole number in its range "
				      "(docs/limits.md)"), -1;
	*v = (long)x;
	return 1;
}

/* Decimals of the seconds past the sixth dropped: .NET's round-trip
 * time (N.I.N.A., ASCOM programs) writes seven; a microsecond is far
 * below any exposure. */
static void seconds_to_micro(char *t)
{
	char *dot = strchr(t, '.'), *end;

	if (!dot)
		return;
	for (end = dot + 1; *end >= '0' && *end <= '9'; end++)
		;
	if (end - dot > 7)
		memmove(dot + 7, end, strlen(end) + 1);
}

static int keywords(fitsfile *f, const char *path,
		    struct stray_import_header *h, struct stray_error *err)
{
	char text[STRAY_IMPORT_TEXT_MAX];
	long xb = 1, yb = 1, x0 = 0, y0 = 0;
	int k, got, gx, gy;

	if (exposure(f, path, h, err) || frame_kind(f, path, h, err) ||
	    key_str(f, path, "FILTER", h->filter, sizeof(h->filter), err) < 0 ||
	    key_str(f, path, "INSTRUME", h->instrume, sizeof(h->instrume),
		    err) < 0 ||
	    (got = key_str(f, path, "ROWORDER", text, sizeof(text), err)) < 0 ||
	    (h->has_rotatang = key_num(f, path, "ROTATANG", &h->rotatang_deg,
				       err)) < 0 ||
	    key_whole(f, path, "XBINNING", 1, 64, &xb, err) < 0 ||
	    key_whole(f, path, "YBINNING", 1, 64, &yb, err) < 0 ||
	    (gx = key_whole(f, path, "XORGSUBF", 0, 65535, &x0, err)) < 0 ||
	    (gy = key_whole(f, path, "YORGSUBF", 0, 65535, &y0, err)) < 0 ||
	    (h->has_satlevel = key_whole(f, path, "SATURATE", 1, 65536,
					 &h->satlevel, err)) < 0)
		return STRAY_EINVAL;
	if (xb != 1 || yb != 1)
		return stray_error_at(err, STRAY_EINVAL, path, 0, xb != 1 ?
			"XBINNING" : "YBINNING", "must be 1: the reduction "
			"works on detector pixels (their Bayer phase); take "
			"the sweep unbinned");
	h->bottom_up = got > 0 && strcasecmp(text, "BOTTOM-UP") == 0;
	if (got > 0 && !h->bottom_up && strcasecmp(text, "TOP-DOWN") != 0) {
		stray_error_at(err, STRAY_EINVAL, path, 0, "ROWORDER",
			       "must be TOP-DOWN or BOTTOM-UP");
		stray_error_text(err, text);
		return STRAY_EINVAL;
	}
	h->has_origin = gx > 0 || gy > 0;
	h->col0 = x0;
	h->row0 = y0;
	for (k = 0; k < STRAY_IMPORT_SETTINGS; k++)
		if ((h->has_setting[k] = key_num(f, path, setting_keys[k],
						 &h->setting[k], err)) < 0)
			return STRAY_EINVAL;
	if ((got = key_str(f, path, "DATE-OBS", text, sizeof(text), err)) < 0)
		return STRAY_EINVAL;
	h->has_date = got > 0;
	if (got > 0)
		seconds_to_micro(text);
	if (got > 0 && stray_sweep_utc_parse(text, &h->date_obs) != STRAY_OK) {
		stray_error_at(err, STRAY_EPARSE, path, 0, "DATE-OBS",
			       "must be a UTC time like 2026-12-02T04:50:00.123");
		stray_error_text(err, text);
		return STRAY_EPARSE;
	}
	return STRAY_OK;
}

/* BITPIX 16 with BZERO 32768 (unsigned), NAXIS 2, sizes held to the
 * bytes the file has (stray/sizes.h). */
static int geometry(fitsfile *f, const char *path, size_t len,
		    struct stray_import_header *h, struct stray_error *err)
{
	LONGLONG head = 0, data = 0, end = 0;
	long naxes[3] = { 0, 0, 0 };
	int status = 0, eq = 0, naxis = 0;
	size_t have = 0;

	if (fits_get_img_equivtype(f, &eq, &status) ||
	    fits_get_img_dim(f, &naxis, &status))
		return fits_bad(path, "BITPIX", "cannot be read", status, err);
	if (eq != USHORT_IMG)
		return stray_error_at(err, STRAY_EINVAL, path, 0, "BITPIX",
			"must be 16 with BZERO 32768 (unsigned 16-bit "
			"counts); other depths would be rescaled counts");
	if (naxis != 2)
		return stray_error_at(err, STRAY_EINVAL, path, 0, "NAXIS",
			"must be 2: one grey plane (a colour or a stack of "
			"frames is not one detector read)");
	if (fits_get_img_size(f, 2, naxes, &status) ||
	    fits_get_hduaddrll(f, &head, &data, &end, &status))
		return fits_bad(path, "NAXIS1", "cannot be read", status, err);
	if (naxes[0] < 1 || naxes[1] < 1 || naxes[0] > STRAY_SWEEP_COLS_MAX ||
	    naxes[1] > STRAY_SWEEP_ROWS_MAX)
		return stray_error_at(err, STRAY_EINVAL, path, 0, "NAXIS2",
			"image size out of range (1..8192 rows, 1..65536 "
			"columns)");
	if (data >= 0 && (LONGLONG)len > data)
		have = len - (size_t)data;
	h->n_cols = (size_t)naxes[0];
	h->n_rows = (size_t)naxes[1];
	return stray_size_check2(h->n_cols, h->n_rows, 2,
				 STRAY_SWEEP_FRAME_BYTES_MAX, have, path,
				 "NAXIS1 x NAXIS2", NULL, err);
}

/* The counts, first row the detector's first. */
static int pixels(fitsfile *f, const char *path, struct stray_import_header *h,
		  uint16_t **px, struct stray_error *err)
{
	size_t n = h->n_rows * h->n_cols, r;
	unsigned short nul = 0;
	int status = 0, anynul = 0;
	uint16_t *p = malloc(n * sizeof(*p));

	if (!p)
		return stray_error_at(err, STRAY_ENOMEM, path, 0, "data",
				      "no memory for the frame");
	if (fits_read_img(f, TUSHORT, 1, (LONGLONG)n, &nul, p, &anynul,
			  &status)) {
		free(p);
		return fits_bad(path, "data", "pixels cannot be read", status,
				err);
	}
	for (r = 0; h->bottom_up && r < h->n_rows / 2; r++) {
		uint16_t *a = p + r * h->n_cols;
		uint16_t *b = p + (h->n_rows - 1 - r) * h->n_cols;
		size_t c;

		for (c = 0; c < h->n_cols; c++) {
			uint16_t t = a[c];

			a[c] = b[c];
			b[c] = t;
		}
	}
	*px = p;
	return STRAY_OK;
}

static int read_fits(const char *path, const struct stray_sweep_buf *b,
		     struct stray_import_header *h, uint16_t **px,
		     struct stray_error *err)
{
	/* cfitsio parses a memory file's name too: a fixed one here. */
	void *mem = b->data;
	size_t size = (b->len + 2879) / 2880 * 2880;
	fitsfile *f = NULL;
	int status = 0, rc;

	if (fits_open_memfile(&f, "frame.fits", READONLY, &mem, &size, 0,
			      NULL, &status))
		return fits_bad(path, "file", "not a readable FITS image",
				status, err);
	rc = geometry(f, path, b->len, h, err);
	if (rc == STRAY_OK)
		rc = keywords(f, path, h, err);
	if (rc == STRAY_OK && px)
		rc = pixels(f, path, h, px, err);
	status = 0;
	fits_close_file(f, &status);
	fits_clear_errmsg();
	return rc;
}

int stray_import_frame_read(const char *path, const struct stray_sweep_buf *b,
			    struct stray_import_header *h, uint16_t **px,
			    struct stray_error *err)
{
	static const unsigned char le[4] = { 'I', 'I', 42, 0 };
	static const unsigned char be[4] = { 'M', 'M', 0, 42 };

	memset(h, 0, sizeof(*h));
	h->light = -1;
	if (px)
		*px = NULL;
	if (b->len >= 9 && memcmp(b->data, "SIMPLE  =", 9) == 0) {
		h->format = STRAY_IMPORT_FITS;
		return read_fits(path, b, h, px, err);
	}
	if (b->len >= 4 && (memcmp(b->data, le, 4) == 0 ||
			    memcmp(b->data, be, 4) == 0)) {
		h->format = STRAY_IMPORT_TIFF;
		return stray_import_tiff_read(path, b, h, px, err);
	}
	return stray_error_at(err, STRAY_EINVAL, path, 0, "file",
			      "is neither FITS nor (classic) TIFF");
}
