/*
 * fits_read.c - a lab frame read through cfitsio (sweep_store.h): header
 * keywords FRAMETYP, ANGLE, EXPTIME, NDTRANS, SEQNUM, ROWS, COL0, ROW0,
 * SATLEVEL (and the optional MONITOR and ANGLERB), then the 16-bit image.
 */
#include <errno.h>
#include <fitsio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sizes.h"
#include "stray/sweep_store.h"

/* A cfitsio failure: keyword (or part) and cfitsio's own words. */
static int fits_fail(const char *path, const char *field, const char *why,
		     int status, struct stray_error *err)
{
	char text[FLEN_STATUS] = "";

	if (status && status != KEY_NO_EXIST)	/* else says it twice */
		fits_get_errstatus(status, text);
	fits_clear_errmsg();
	stray_error_at(err, status == KEY_NO_EXIST ? STRAY_ENOTFOUND
						    : STRAY_EPARSE,
		       path, 0, field, why);
	stray_error_text(err, text);
	return err ? err->code : STRAY_EPARSE;
}

/*
 * The raw value text of a keyword (cfitsio's ffgkey), converted here with
 * strtod: cfitsio 4.2's own numeric conversion (ffc2j) aborts on some
 * malformed values (found by fuzz_reduce_input).  status KEY_NO_EXIST
 * when the keyword is absent.
 */
static int key_number(struct stray_sweep_fits *f, const char *key, double *v,
		      int *status)
{
	char text[FLEN_VALUE], *end;

	if (fits_read_keyword(f->fptr, key, text, NULL, status))
		return *status;
	errno = 0;
	*v = strtod(text, &end);
	while (*end == ' ')
		end++;
	if (end == text || *end != '\0' || errno)
		*status = BAD_C2D;
	return *status;
}

static int key_double(struct stray_sweep_fits *f, const char *key, double *v,
		      struct stray_error *err)
{
	int status = 0;

	if (key_number(f, key, v, &status))
		return fits_fail(f->path, key, status == KEY_NO_EXIST ?
			"required keyword missing" : "is not a number",
			status, err);
	if (!isfinite(*v))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, key,
				      "is not finite");
	return STRAY_OK;
}

static int key_long(struct stray_sweep_fits *f, const char *key, long *v,
		    int required, struct stray_error *err)
{
	double x;
	int status = 0;

	if (key_number(f, key, &x, &status)) {
		if (status == KEY_NO_EXIST && !required) {
			fits_clear_errmsg();
			return STRAY_OK;
		}
		return fits_fail(f->path, key, status == KEY_NO_EXIST ?
			"required keyword missing" : "is not an integer",
			status, err);
	}
	if (!(x == floor(x) && fabs(x) <= 1e9))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, key,
				      "is not an integer within +/-1e9");
	*v = (long)x;
	return STRAY_OK;
}

int stray_sweep_rows_parse(const char *path, const char *text, long *rows,
		     size_t n, struct stray_error *err)
{
	const char *s = text;
	size_t k;

	for (k = 0; k < n; k++) {
		char *end;
		long v;

		errno = 0;
		v = strtol(s, &end, 10);
		if (end == s || errno || v < 0)
			break;
		rows[k] = v;
		s = end;
		if (k + 1 < n) {
			if (*s != ',')
				break;
			s++;
		}
	}
	if (k != n || *s != '\0') {
		stray_error_at(err, STRAY_EPARSE, path, 0, STRAY_SWEEP_KEY_ROWS,
			"must list one detector row per stored row (NAXIS2)");
		stray_error_text(err, text);
		return STRAY_EPARSE;
	}
	return STRAY_OK;
}

static int read_rows(struct stray_sweep_fits *f, struct stray_error *err)
{
	char *text = NULL;
	size_t k;
	int status = 0, rc;

	f->h.has_rows = 0;
	if (fits_read_key_longstr(f->fptr, STRAY_SWEEP_KEY_ROWS, &text, NULL,
				  &status)) {
		if (status != KEY_NO_EXIST)
			return fits_fail(f->path, STRAY_SWEEP_KEY_ROWS,
					 "cannot be read",
					 status, err);
		fits_clear_errmsg();
		for (k = 0; k < f->h.n_rows; k++)	/* full frame */
			f->h.det_row[k] = f->h.row0 + (long)k;
		return STRAY_OK;
	}
	f->h.has_rows = 1;
	rc = stray_sweep_rows_parse(f->path, text, f->h.det_row, f->h.n_rows,
				    err);
	fits_free_memory(text, &status);
	return rc;
}

static int read_type(struct stray_sweep_fits *f, struct stray_error *err)
{
	char text[FLEN_VALUE];
	int status = 0;

	if (fits_read_key(f->fptr, TSTRING, STRAY_SWEEP_KEY_FRAMETYP, text,
			  NULL, &status))
		return fits_fail(f->path, STRAY_SWEEP_KEY_FRAMETYP,
				 status == KEY_NO_EXIST ?
			"required keyword missing" : "cannot be read",
			status, err);
	f->h.type = stray_sweep_frametyp_parse(text);
	if (f->h.type < 0) {
		stray_error_at(err, STRAY_EPARSE, f->path, 0,
			       STRAY_SWEEP_KEY_FRAMETYP,
			       "must be DARK, AMBIENT or FULL");
		stray_error_text(err, text);
		return STRAY_EPARSE;
	}
	return STRAY_OK;
}

/* NAXIS1 x NAXIS2 against the bytes after the header, before anyone
 * sizes a buffer by them (a 6 KB file may claim 65536 x 8192 pixels). */
static int check_size(struct stray_sweep_fits *f, struct stray_error *err)
{
	LONGLONG head = 0, data = 0, end = 0;
	size_t px = (size_t)(f->bitpix < 0 ? -f->bitpix : f->bitpix) / 8;
	size_t have = 0;
	int status = 0;

	if (!f->mem)		/* every reader opens from memory */
		return STRAY_OK;
	if (fits_get_hduaddrll(f->fptr, &head, &data, &end, &status))
		return fits_fail(f->path, "NAXIS", "cannot be read", status,
				 err);
	if (data >= 0 && (LONGLONG)f->data_len > data)
		have = f->data_len - (size_t)data;
	return stray_size_check2(f->h.n_cols, f->h.n_rows, px,
				 STRAY_SWEEP_FRAME_BYTES_MAX, have, f->path,
				 "NAXIS1 x NAXIS2", NULL, err);
}

static int read_geometry(struct stray_sweep_fits *f, struct stray_error *err)
{
	long naxes[2];
	int status = 0, bitpix = 0, naxis = 0;

	if (fits_get_img_equivtype(f->fptr, &bitpix, &status) ||
	    fits_get_img_type(f->fptr, &f->bitpix, &status) ||
	    fits_get_img_dim(f->fptr, &naxis, &status))
		return fits_fail(f->path, "BITPIX", "cannot be read", status,
				 err);
	f->equiv_bitpix = bitpix;
	if (bitpix != USHORT_IMG && bitpix != SHORT_IMG)
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, "BITPIX",
			"must be 16 (with BZERO 32768 for unsigned counts)");
	if (naxis != 2)
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, "NAXIS",
				      "must be 2 (rows x columns)");
	if (fits_get_img_size(f->fptr, 2, naxes, &status))
		return fits_fail(f->path, "NAXIS1", "cannot be read", status,
				 err);
	if (naxes[0] < 1 || naxes[1] < 1 || naxes[1] > STRAY_SWEEP_ROWS_MAX ||
	    naxes[0] > 65536)
		return stray_error_at(err, STRAY_EPARSE, f->path, 0, "NAXIS2",
			"image size out of range (1..8192 rows, 1..65536 columns)");
	f->h.n_cols = (size_t)naxes[0];
	f->h.n_rows = (size_t)naxes[1];
	return check_size(f, err);
}

/* A lab keyword a flight frame may leave out: def when absent there. */
static int lab_double(struct stray_sweep_fits *f, const char *key, double *v,
		      double def, struct stray_error *err)
{
	char text[FLEN_VALUE];
	int status = 0;

	if (f->flight && fits_read_keyword(f->fptr, key, text, NULL, &status)) {
		fits_clear_errmsg();
		*v = def;
		if (status == KEY_NO_EXIST)
			return STRAY_OK;
	}
	return key_double(f, key, v, err);
}

static int lab_long(struct stray_sweep_fits *f, const char *key, long *v,
		    long def, struct stray_error *err)
{
	*v = def;
	return key_long(f, key, v, !f->flight, err);
}

static int lab_type(struct stray_sweep_fits *f, struct stray_error *err)
{
	char text[FLEN_VALUE];
	int status = 0;

	if (f->flight && fits_read_keyword(f->fptr, STRAY_SWEEP_KEY_FRAMETYP,
					   text, NULL, &status) &&
	    status == KEY_NO_EXIST) {
		fits_clear_errmsg();
		f->h.type = STRAY_SWEEP_FULL;
		return STRAY_OK;
	}
	return read_type(f, err);
}

static int read_header(struct stray_sweep_fits *f, struct stray_error *err)
{
	struct stray_sweep_header *h = &f->h;
	int rc, status = 0;

	h->col0 = h->row0 = 0;
	if ((rc = read_geometry(f, err)) || (rc = lab_type(f, err)) ||
	    (rc = lab_double(f, STRAY_SWEEP_KEY_ANGLE, &h->angle_deg, 0.0, err)) ||
	    (rc = key_double(f, STRAY_SWEEP_KEY_EXPTIME, &h->exptime_s, err)) ||
	    (rc = lab_double(f, STRAY_SWEEP_KEY_NDTRANS, &h->ndtrans, 1.0, err)) ||
	    (rc = lab_long(f, STRAY_SWEEP_KEY_SEQNUM, &h->seqnum, 0, err)) ||
	    (rc = lab_long(f, STRAY_SWEEP_KEY_SATLEVEL, &h->satlevel, 65535,
			   err)) ||
	    (rc = key_long(f, STRAY_SWEEP_KEY_COL0, &h->col0, 0, err)) ||
	    (rc = key_long(f, STRAY_SWEEP_KEY_ROW0, &h->row0, 0, err)) ||
	    (rc = read_rows(f, err)))
		return rc;
	h->has_monitor = 0;
	h->monitor = 1.0;
	if (key_number(f, STRAY_SWEEP_KEY_MONITOR, &h->monitor, &status) == 0)
		h->has_monitor = 1;
	else if (status != KEY_NO_EXIST)
		return fits_fail(f->path, STRAY_SWEEP_KEY_MONITOR,
				 "is not a number", status,
				 err);
	fits_clear_errmsg();
	status = 0;
	h->has_angle_rb = 0;
	h->angle_rb_deg = h->angle_deg;
	if (key_number(f, STRAY_SWEEP_KEY_ANGLERB, &h->angle_rb_deg,
		       &status) == 0)
		h->has_angle_rb = 1;
	else if (status != KEY_NO_EXIST)
		return fits_fail(f->path, STRAY_SWEEP_KEY_ANGLERB,
				 "is not a number", status, err);
	fits_clear_errmsg();
	if (h->has_angle_rb && !isfinite(h->angle_rb_deg))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0,
				      STRAY_SWEEP_KEY_ANGLERB,
				      "must be finite");
	if (!(h->exptime_s > 0.0))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0,
				      STRAY_SWEEP_KEY_EXPTIME,
				      "must be > 0");
	if (!(h->ndtrans > 0.0 && h->ndtrans <= 1.0))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0,
				      STRAY_SWEEP_KEY_NDTRANS,
				      "must be in (0, 1]");
	if (!(isfinite(h->monitor) && h->monitor > 0.0))
		return stray_error_at(err, STRAY_EPARSE, f->path, 0,
				      STRAY_SWEEP_KEY_MONITOR,
				      "must be finite and > 0");
	if (h->satlevel < 1 || h->satlevel > 65536)
		return stray_error_at(err, STRAY_EPARSE, f->path, 0,
				      STRAY_SWEEP_KEY_SATLEVEL,
				      "must be in 1..65536");
	return STRAY_OK;
}

/* Read the header of the opened f; f closed again on an error. */
static int header_or_close(struct stray_sweep_fits *f,
			   struct stray_error *err)
{
	int rc = read_header(f, err);

	if (rc != STRAY_OK)
		stray_sweep_fits_close(f);
	return rc;
}

/* Open f's image in f->mem (f->mem_size bytes) and read its header;
 * f closed again on an error. */
static int open_memory(struct stray_sweep_fits *f, const char *name,
		       struct stray_error *err)
{
	int status = 0;

	/* cfitsio parses a memory file's name too ("x[1]" moves to HDU
	 * 1): it gets a fixed one, messages the real name. */
	if (fits_open_memfile((fitsfile **)&f->fptr, "frame.fits", READONLY,
			      &f->mem, &f->mem_size, 0, NULL, &status)) {
		stray_sweep_fits_close(f);
		return fits_fail(name, "file", "not a readable FITS image",
				 status, err);
	}
	return header_or_close(f, err);
}

int stray_sweep_fits_open(const char *path, struct stray_sweep_fits *f,
		    struct stray_error *err)
{
	struct stray_sweep_buf b = { NULL, 0, 0 };
	int rc;

	f->path = path;
	f->fptr = NULL;
	f->mem = NULL;
	f->mem_borrowed = 0;
	f->flight = 0;
	/* Read by the toolkit (no symlink, FIFO or device) and decoded from
	 * memory: cfitsio never sees the name, whose "(", "[" and "!" it
	 * would take as instructions (write a copy, filter the pixels). */
	if ((rc = stray_sweep_file_load(path, &b, err)) != STRAY_OK) {
		stray_sweep_buf_free(&b);
		return rc;
	}
	f->mem = b.data;	/* zero-padded to whole blocks; f's now */
	f->mem_size = b.len ? (b.len + 2879) / 2880 * 2880 : 2880;
	f->data_len = b.len;
	return open_memory(f, path, err);
}

int stray_sweep_fits_open_mem(const char *name, const void *data, size_t len,
			struct stray_sweep_fits *f, struct stray_error *err)
{
	size_t padded = (len + 2879) / 2880 * 2880;

	f->path = name;
	f->fptr = NULL;
	/* cfitsio's memory driver reads whole 2880-byte blocks: pad a copy
	 * with zeros so a short buffer is never read past its end. */
	f->mem = calloc(1, padded ? padded : 2880);
	f->mem_size = padded ? padded : 2880;
	f->mem_borrowed = 0;
	f->flight = 0;
	f->data_len = len;
	if (!f->mem)
		return stray_error_at(err, STRAY_ENOMEM, name, 0, "file",
				      "no memory for the frame");
	memcpy(f->mem, data, len);
	return open_memory(f, name, err);
}

static int open_buf(const char *name, struct stray_sweep_buf *b,
		    struct stray_sweep_fits *f, int flight,
		    struct stray_error *err)
{
	f->path = name;
	f->fptr = NULL;
	f->mem = b->data;	/* zero-padded to whole blocks */
	f->mem_size = (b->len + 2879) / 2880 * 2880;
	f->mem_borrowed = 1;
	f->data_len = b->len;
	f->flight = flight;
	return open_memory(f, name, err);
}

int stray_sweep_fits_open_buf(const char *name, struct stray_sweep_buf *b,
			      struct stray_sweep_fits *f,
			      struct stray_error *err)
{
	return open_buf(name, b, f, 0, err);
}

int stray_sweep_fits_open_flight_buf(const char *name,
				     struct stray_sweep_buf *b,
				     struct stray_sweep_fits *f,
				     struct stray_error *err)
{
	return open_buf(name, b, f, 1, err);
}

/* Whether the image is unsigned 16-bit as the lab writes it (BITPIX 16,
 * BSCALE 1, BZERO 32768): then the stored value is the count with its
 * top bit flipped, big-endian. */
static int plain_u16(struct stray_sweep_fits *f)
{
	double zero = 0.0, scale = 1.0;
	int status = 0;

	if (f->bitpix != SHORT_IMG || f->equiv_bitpix != USHORT_IMG)
		return 0;
	if (fits_read_key_dbl(f->fptr, "BZERO", &zero, NULL, &status))
		zero = 0.0;
	status = 0;
	if (fits_read_key_dbl(f->fptr, "BSCALE", &scale, NULL, &status))
		scale = 1.0;
	fits_clear_errmsg();
	return zero == 32768.0 && scale == 1.0;
}

/* What cfitsio's ffi2u2 does for BSCALE 1, BZERO 32768, in a loop the
 * compiler vectorises. */
static void decode_u16(const unsigned char *restrict p, uint16_t *restrict pix,
		       size_t n)
{
	size_t i;

	for (i = 0; i < n; i++)
		pix[i] = (uint16_t)(((unsigned)p[2 * i] << 8 |
				     (unsigned)p[2 * i + 1]) ^ 0x8000u);
}

int stray_sweep_fits_read(struct stray_sweep_fits *f, uint16_t *pix,
		    struct stray_error *err)
{
	long n = (long)(f->h.n_rows * f->h.n_cols);
	/* bytes a stored pixel takes: BITPIX 8, 16, 32, 64, -32 or -64 */
	LONGLONG px_bytes = f->bitpix < 0 ? -f->bitpix / 8 : f->bitpix / 8;
	int status = 0, anynul = 0;
	unsigned short nul = 0;
	LONGLONG head, data, end;

	/* cfitsio's memory driver does not bound its reads (and reads the
	 * zeros padding the buffer to whole blocks): check first. */
	if (f->mem && (fits_get_hduaddrll(f->fptr, &head, &data, &end,
					  &status) ||
		       (LONGLONG)f->data_len < data + px_bytes * n))
		return fits_fail(f->path, "data",
			"truncated: fewer pixels than NAXIS1 x NAXIS2", status,
			err);
	if (f->mem && plain_u16(f)) {
		decode_u16((const unsigned char *)f->mem + data, pix,
			   (size_t)n);
		return STRAY_OK;
	}

	if (fits_read_img(f->fptr, TUSHORT, 1, n, &nul, pix, &anynul,
			  &status))
		return fits_fail(f->path, "data",
			status == END_OF_FILE || status == READ_ERROR
				? "truncated: fewer pixels than NAXIS1 x NAXIS2"
				: "pixels cannot be read",
			status, err);
	return STRAY_OK;
}

void stray_sweep_fits_close(struct stray_sweep_fits *f)
{
	int status = 0;

	if (f->fptr)
		fits_close_file(f->fptr, &status);
	fits_clear_errmsg();
	f->fptr = NULL;
	if (!f->mem_borrowed)
		free(f->mem);
	f->mem = NULL;
	f->mem_borrowed = 0;
}
