/*
 * sweep_fits.h - one lab frame from its FITS file (docs/formats.md)
 * through cfitsio: the header keywords, then the pixels into a caller
 * buffer, one frame at a time.
 */
#ifndef STRAY_TOOLS_SWEEP_FITS_H
#define STRAY_TOOLS_SWEEP_FITS_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

/* Rows a frame may store (the largest detector has 1944). */
#define SWEEP_ROWS_MAX 8192

struct sweep_header {
	int type;		/* enum sweep_frametyp */
	double angle_deg, exptime_s, ndtrans;
	double monitor;		/* MONITOR, 1 when absent */
	int has_monitor;
	long seqnum, col0, row0, satlevel;
	size_t n_rows, n_cols;	/* NAXIS2, NAXIS1 */
	int has_rows;		/* ROWS present (row-sampled frame) */
	long det_row[SWEEP_ROWS_MAX];	/* detector row of each stored row */
};

struct sweep_fits {
	void *fptr;		/* fitsfile *, opaque here */
	const char *path;
	struct sweep_header h;
	/* An in-memory file: cfitsio keeps the addresses of these two. */
	void *mem;
	size_t mem_size;
};

/* Open and read the header; errors name the file and the keyword. */
int sweep_fits_open(const char *path, struct sweep_fits *f,
		    struct stray_error *err);

/* Open an in-memory FITS image (the fuzz target's entry). */
int sweep_fits_open_mem(const char *name, const void *data, size_t len,
			struct sweep_fits *f, struct stray_error *err);

/* Read all n_rows * n_cols pixels into pix (row-major). */
int sweep_fits_read(struct sweep_fits *f, uint16_t *pix,
		    struct stray_error *err);

void sweep_fits_close(struct sweep_fits *f);

/* Parse a ROWS value "960,961,..." into n detector rows. */
int sweep_rows_parse(const char *path, const char *text, long *rows,
		     size_t n, struct stray_error *err);

#endif /* STRAY_TOOLS_SWEEP_FITS_H */
