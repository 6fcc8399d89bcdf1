/*
 * import_tiff.c - a 16-bit TIFF written by a camera SDK or a capture
 * program, decoded by libtiff from the bytes already in memory (the file
 * was read by the toolkit: no symlink or FIFO followed, the same bytes
 * hashed).  One page of one grey 16-bit unsigned sample per pixel, in
 * strips, any compression libtiff decodes; 8-bit, RGB, float, tiled and
 * multi-page files are refused with the tag that says so.  A TIFF has no
 * exposure, angle or frame type: those come from the log alone.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tiffio.h>

#include "import_priv.h"
#include "stray/errfmt.h"
#include "stray/sizes.h"

/* The file in memory as libtiff's client I/O sees it. */
struct mem {
	const unsigned char *data;
	toff_t len, pos;
};

static tmsize_t mem_read(thandle_t h, void *buf, tmsize_t n)
{
	struct mem *m = (struct mem *)h;
	toff_t left = m->pos < m->len ? m->len - m->pos : 0;

	if (n < 0)
		return -1;
	if ((toff_t)n > left)
		n = (tmsize_t)left;
	memcpy(buf, m->data + m->pos, (size_t)n);
	m->pos += (toff_t)n;
	return n;
}

static tmsize_t mem_write(thandle_t h, void *buf, tmsize_t n)
{
	(void)h;
	(void)buf;
	(void)n;
	return -1;		/* read only */
}

static toff_t mem_seek(thandle_t h, toff_t off, int whence)
{
	struct mem *m = (struct mem *)h;
	toff_t base = whence == SEEK_CUR ? m->pos : whence == SEEK_END ?
		      m->len : 0;

	if (off > (toff_t)-1 - base)
		return (toff_t)-1;
	m->pos = base + off;
	return m->pos;
}

static int mem_close(thandle_t h)
{
	(void)h;
	return 0;
}

static toff_t mem_size(thandle_t h)
{
	return ((struct mem *)h)->len;
}

/* libtiff's own words for the last error (one line, no stderr). */
static char tiff_msg[160];

static void on_error(const char *module, const char *fmt, va_list ap)
{
	(void)module;
	vsnprintf(tiff_msg, sizeof(tiff_msg), fmt, ap);
}

static int tiff_bad(const char *path, const char *tag, const char *why,
		    const char *text, struct stray_error *err)
{
	stray_error_at(err, STRAY_EINVAL, path, 0, tag, why);
	stray_error_text(err, text);
	return STRAY_EINVAL;
}

static int tags(TIFF *t, const char *path, struct stray_import_header *h,
		struct stray_error *err)
{
	uint32_t w = 0, ht = 0;
	uint16_t bits = 1, spp = 1, fmt = SAMPLEFORMAT_UINT, photo = 0;
	char text[32];

	TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
	TIFFGetField(t, TIFFTAG_IMAGELENGTH, &ht);
	TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bits);
	TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
	TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &fmt);
	if (!TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photo))
		photo = PHOTOMETRIC_MINISBLACK;
	snprintf(text, sizeof(text), "%u", spp);
	if (spp != 1)
		return tiff_bad(path, "SamplesPerPixel", "must be 1: one grey "
			"plane (an RGB or colour image is not the detector's "
			"raw counts)", text, err);
	snprintf(text, sizeof(text), "%u", bits);
	if (bits != 16)
		return tiff_bad(path, "BitsPerSample", "must be 16 (an 8-bit "
			"image is not the camera's counts)", text, err);
	snprintf(text, sizeof(text), "%u", fmt);
	if (fmt != SAMPLEFORMAT_UINT)
		return tiff_bad(path, "SampleFormat", "must be 1 (unsigned "
				"integer counts)", text, err);
	snprintf(text, sizeof(text), "%u", photo);
	if (photo != PHOTOMETRIC_MINISBLACK)
		return tiff_bad(path, "PhotometricInterpretation", "must be 1 "
			"(BlackIsZero): counts, not an inverted or colour "
			"image", text, err);
	if (TIFFIsTiled(t))
		return tiff_bad(path, "TileWidth", "tiled TIFF: save the "
				"frames in strips (the default of most "
				"writers)", "", err);
	if (TIFFReadDirectory(t))
		return tiff_bad(path, "file", "has more than one page: one "
				"frame per file", "", err);
	snprintf(text, sizeof(text), "%u x %u", w, ht);
	if (w < 1 || ht < 1 || w > STRAY_SWEEP_COLS_MAX ||
	    ht > STRAY_SWEEP_ROWS_MAX)
		return tiff_bad(path, "ImageWidth", "image size out of range "
				"(1..8192 rows, 1..65536 columns)", text, err);
	h->n_cols = w;
	h->n_rows = ht;
	return STRAY_OK;
}

static int pixels(TIFF *t, const char *path, struct stray_import_header *h,
		  uint16_t **px, struct stray_error *err)
{
	size_t n, r;
	uint16_t *p;

	if (stray_size_check2(h->n_cols, h->n_rows, 2,
			      STRAY_SWEEP_FRAME_BYTES_MAX, SIZE_MAX, path,
			      "ImageWidth x ImageLength", &n, err))
		return STRAY_EINVAL;
	if (TIFFScanlineSize(t) != (tmsize_t)(h->n_cols * 2))
		return tiff_bad(path, "StripByteCounts", "scanline size is not "
				"2 bytes a pixel", "", err);
	if (!(p = malloc(n)))
		return stray_error_at(err, STRAY_ENOMEM, path, 0, "data",
				      "no memory for the frame");
	for (r = 0; r < h->n_rows; r++)
		if (TIFFReadScanline(t, p + r * h->n_cols, (uint32_t)r, 0) < 0) {
			free(p);
			return tiff_bad(path, "StripOffsets", "pixels cannot "
					"be read (truncated or corrupt)",
					tiff_msg, err);
		}
	*px = p;
	return STRAY_OK;
}

int stray_import_tiff_read(const char *path, const struct stray_sweep_buf *b,
			   struct stray_import_header *h, uint16_t **px,
			   struct stray_error *err)
{
	struct mem m = { b->data, b->len, 0 };
	TIFF *t;
	int rc;

	tiff_msg[0] = '\0';
	TIFFSetErrorHandler(on_error);
	TIFFSetWarningHandler(NULL);	/* unknown private tags: harmless */
	/* "rm": read, no memory mapping (our own buffer already). */
	t = TIFFClientOpen("frame.tif", "rm", (thandle_t)&m, mem_read,
			   mem_write, mem_seek, mem_close, mem_size, NULL,
			   NULL);
	if (!t)
		return tiff_bad(path, "file", "not a readable TIFF", tiff_msg,
				err);
	rc = tags(t, path, h, err);
	/* tags() read the next page to count them: back to the first. */
	if (rc == STRAY_OK && !TIFFSetDirectory(t, 0))
		rc = tiff_bad(path, "file", "first page cannot be re-read",
			      tiff_msg, err);
	if (rc == STRAY_OK && px)
		rc = pixels(t, path, h, px, err);
	TIFFClose(t);
	return rc;
}
