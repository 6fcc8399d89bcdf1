/*
 * sweep_store.h - the sweep folder on disk (docs/formats.md, "Lab
 * frames"), the one place that knows its format: one FITS file per frame
 * and manifest.csv with one row per frame,
 *   file,frametyp,angle_deg,exptime_s,ndtrans,seqnum,sha256
 * The writer (strayrigd) appends a row only after the frame file is
 * complete, fsynced and renamed into place, so after a crash every row
 * names a whole file and a file without a row is an orphan to be retaken;
 * one writer per folder (an exclusive flock on manifest.csv).  The reader
 * (the lab-sweep reduction) parses the manifest with libcsv, checks each
 * frame's SHA-256 (OpenSSL) and reads frames through cfitsio.
 */
#ifndef STRAY_SWEEP_STORE_H
#define STRAY_SWEEP_STORE_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

/* Frame types (FRAMETYP / frametyp), thesis table 3.1. */
enum stray_sweep_frametyp {
	STRAY_SWEEP_DARK, STRAY_SWEEP_AMBIENT, STRAY_SWEEP_FULL,
	STRAY_SWEEP_FRAMETYP_COUNT
};

/* The manifest: its name and columns. */
#define STRAY_SWEEP_MANIFEST "manifest.csv"
#define STRAY_SWEEP_COL_FILE "file"
#define STRAY_SWEEP_COL_FRAMETYP "frametyp"
#define STRAY_SWEEP_COL_ANGLE "angle_deg"
#define STRAY_SWEEP_COL_EXPTIME "exptime_s"
#define STRAY_SWEEP_COL_NDTRANS "ndtrans"
#define STRAY_SWEEP_COL_SEQNUM "seqnum"
#define STRAY_SWEEP_COL_SHA256 "sha256"
/* optional: UTC at the exposure's start, 2026-12-02T04:50:00.123Z (a
 * folder written before it has none; its frames then have no time) */
#define STRAY_SWEEP_COL_DATE_OBS "date_obs"
#define STRAY_SWEEP_MANIFEST_HEADER STRAY_SWEEP_COL_FILE "," \
	STRAY_SWEEP_COL_FRAMETYP "," STRAY_SWEEP_COL_ANGLE "," \
	STRAY_SWEEP_COL_EXPTIME "," STRAY_SWEEP_COL_NDTRANS "," \
	STRAY_SWEEP_COL_SEQNUM "," STRAY_SWEEP_COL_SHA256 "," \
	STRAY_SWEEP_COL_DATE_OBS "\n"

/* FITS keywords of a frame (primary HDU, BITPIX 16, BZERO 32768). */
#define STRAY_SWEEP_KEY_FRAMETYP "FRAMETYP"
#define STRAY_SWEEP_KEY_ANGLE "ANGLE"		/* [deg] */
#define STRAY_SWEEP_KEY_EXPTIME "EXPTIME"	/* [s] */
#define STRAY_SWEEP_KEY_NDTRANS "NDTRANS"
#define STRAY_SWEEP_KEY_SEQNUM "SEQNUM"
#define STRAY_SWEEP_KEY_ROWS "ROWS"		/* row-sampled frames only */
#define STRAY_SWEEP_KEY_COL0 "COL0"
#define STRAY_SWEEP_KEY_ROW0 "ROW0"
#define STRAY_SWEEP_KEY_SATLEVEL "SATLEVEL"	/* [DN] */
#define STRAY_SWEEP_KEY_MONITOR "MONITOR"	/* optional, 1 = nominal */
/* optional [deg]: the stage's read-back angle (position counter) for
 * the frame, where ANGLE is the commanded one */
#define STRAY_SWEEP_KEY_ANGLERB "ANGLERB"
/* optional: UTC at the exposure's start and end (ISO 8601), TIMESYS UTC */
#define STRAY_SWEEP_KEY_DATE_OBS "DATE-OBS"
#define STRAY_SWEEP_KEY_DATE_END "DATE-END"

/* A UTC instant, in seconds since 1970-01-01 (leap seconds not counted,
 * as time_t), as 2026-12-02T04:50:00.123Z, and back; the parse takes
 * that form with 0-6 decimals and an optional Z, years 1970-9999, and
 * returns STRAY_EPARSE otherwise. */
#define STRAY_SWEEP_UTC_LEN 32
void stray_sweep_utc_format(double t, char *out, size_t size);
int stray_sweep_utc_parse(const char *text, double *t);

#define STRAY_SWEEP_FILE_MAX 256
#define STRAY_SWEEP_DIR_MAX 1024
#define STRAY_SWEEP_SHA256_HEX 65
/* Rows a frame may store (the largest detector has 1944). */
#define STRAY_SWEEP_ROWS_MAX 8192
/* Columns a frame may store, and the pixel bytes that makes at most. */
#define STRAY_SWEEP_COLS_MAX 65536
#define STRAY_SWEEP_FRAME_BYTES_MAX \
	((size_t)STRAY_SWEEP_COLS_MAX * STRAY_SWEEP_ROWS_MAX * 2)

/* FRAMETYP text to enum; -1 when unknown. */
int stray_sweep_frametyp_parse(const char *text);

/*
 * A frame file listed twice would be counted twice (a manifest, an import
 * log): *dup is the index of the row that repeats an earlier row's file,
 * the earliest such by line, or n when none.  rows: n records of size
 * bytes, the file name a char array at name_off, the line a long at
 * line_off.  STRAY_OK, or STRAY_ENOMEM.
 */
int stray_sweep_repeated_file(const void *rows, size_t n, size_t size,
			      size_t name_off, size_t line_off, size_t *dup);
/* Enum to FRAMETYP text; "?" when out of range. */
const char *stray_sweep_frametyp_name(int type);

/* ---- manifest ---------------------------------------------------------- */

struct stray_sweep_entry {
	char file[STRAY_SWEEP_FILE_MAX];	/* relative to the folder */
	int type;			/* enum stray_sweep_frametyp */
	double angle_deg, exptime_s, ndtrans;
	long seqnum;
	char sha256[STRAY_SWEEP_SHA256_HEX];	/* lower-case hex */
	long line;			/* line in manifest.csv */
	double date_obs;		/* UTC s (date_obs); NAN when absent */
};

/* The rows of a manifest; a writer also holds the folder's lock. */
struct stray_sweep_manifest {
	char dir[STRAY_SWEEP_DIR_MAX];
	size_t n, cap;
	struct stray_sweep_entry *e;
	int writer;			/* 1: lock_fd holds the flock */
	int lock_fd;
	int has_date;			/* the header has date_obs */
};

/*
 * Parse manifest text; name is used in messages.  Lines starting with '#'
 * and blank lines are skipped; the header names the columns (any order,
 * extra columns ignored); every error names the line and the column.
 */
int stray_sweep_manifest_parse(const char *name, const char *text,
			       size_t len, struct stray_sweep_manifest *m,
			       struct stray_error *err);

/* Read DIR/manifest.csv (no lock, nothing changed on disk). */
int stray_sweep_manifest_load(const char *dir,
			      struct stray_sweep_manifest *m,
			      struct stray_error *err);

/* A folder of flight frames without manifest.csv (issue 24): every
 * `*.fits`, `*.fit`, `*.fts` (not hidden) as a FULL row with no hash
 * (sha256 ""), in name order; at most STRAY_SWEEP_FLIGHT_FILES_MAX. */
#define STRAY_SWEEP_FLIGHT_FILES_MAX 100000
int stray_sweep_flight_list(const char *dir, struct stray_sweep_manifest *m,
			    struct stray_error *err);
/* The same for a list of frame files, in the order given (m->dir "":
 * each row's file is its path). */
int stray_sweep_flight_files(char *const *paths, size_t n,
			     struct stray_sweep_manifest *m,
			     struct stray_error *err);

/* Free the rows (and release a writer's lock). */
void stray_sweep_manifest_free(struct stray_sweep_manifest *m);

/* Rows of (angle, type); *first = the first such row or NULL. */
int stray_sweep_manifest_count(const struct stray_sweep_manifest *m,
			       double angle_deg, int type,
			       const struct stray_sweep_entry **first);

/* SHA-256 of a file as lower-case hex (OpenSSL EVP). */
int stray_sweep_sha256_file(const char *path,
			    char hex[STRAY_SWEEP_SHA256_HEX],
			    struct stray_error *err);

/* Compare the SHA-256 of the file at path with hex (64 digits). */
int stray_sweep_sha256_check(const char *path, const char *hex,
			     struct stray_error *err);

/* SHA-256 of bytes in memory; the same check for a file read whole
 * (path names it in errors). */
int stray_sweep_sha256_mem(const void *data, size_t len,
			   char hex[STRAY_SWEEP_SHA256_HEX]);
int stray_sweep_sha256_check_mem(const char *path, const void *data,
				 size_t len, const char *hex,
				 struct stray_error *err);

/* A whole file in memory, reused from frame to frame: len bytes, zeros
 * after them up to the next 2880-byte FITS block (cap bytes held). */
struct stray_sweep_buf {
	unsigned char *data;
	size_t len, cap;
};

/* Read the file at path into b (missing: STRAY_ENOTFOUND, as
 * stray_sweep_sha256_file says it); a symlink, FIFO, device or folder is
 * refused (STRAY_EINVAL) without waiting on it. */
int stray_sweep_file_load(const char *path, struct stray_sweep_buf *b,
			  struct stray_error *err);
void stray_sweep_buf_free(struct stray_sweep_buf *b);

/* ---- writer ------------------------------------------------------------ */

/* A keyword a writer adds to a frame's header (after the lab-frame
 * ones): a double, a long or a string value, with its comment. */
enum stray_sweep_key_kind {
	STRAY_SWEEP_KEY_DOUBLE, STRAY_SWEEP_KEY_LONG, STRAY_SWEEP_KEY_STRING
};

struct stray_sweep_key {
	const char *key;	/* up to 8 characters */
	int kind;		/* enum stray_sweep_key_kind */
	double d;
	long l;
	const char *s;
	const char *comment;
};

/* INSTRUME when a frame names no instrument. */
#define STRAY_SWEEP_INSTRUME_RIG "strayrigd"

/* How a FITS file was made (stray/provenance.h): CREATOR, the program
 * and its git revision, and HISTORY cards with the full command line, in
 * the open header fptr (a fitsfile *); cfitsio's status convention. */
void stray_sweep_fits_provenance(void *fptr, int *status);

/* What a frame's FITS header says beyond its image. */
struct stray_sweep_frame {
	int type;		/* enum stray_sweep_frametyp */
	double angle_deg, exptime_s, ndtrans;
	long seqnum;
	long sat_dn;
	int full_frame;		/* 1: omit ROWS (all detector rows stored) */
	int has_monitor;
	double monitor;		/* lamp level, 1 = nominal (MONITOR) */
	const char *instrument;	/* INSTRUME; NULL: the lab daemon */
	const struct stray_sweep_key *extra;	/* n_extra more keywords */
	size_t n_extra;
	double date_obs, date_end;	/* UTC s; 0: not written */
};

/* A frame's pixels: n_rows x n_cols, row-major, of detector rows[]. */
struct stray_sweep_image {
	size_t n_rows, n_cols;
	long col0;			/* detector column of pixel 0 */
	const uint16_t *rows;		/* detector row of each stored row */
	const uint16_t *px;
};

/* File name of a frame: a+12.000_FULL_000.fits. */
void stray_sweep_frame_filename(const struct stray_sweep_frame *f,
				char *out, size_t size);

/*
 * Open a sweep folder for writing and take its lock (refused while
 * another writer holds it).  New (resume = 0): the folder must not hold
 * a manifest; it is created with its header.  Resume: a torn last line is
 * cut off, every row's file is checked against its sha256, and frame
 * files or temporaries with no row are removed.  Free with
 * stray_sweep_manifest_free.
 */
int stray_sweep_store_open(struct stray_sweep_manifest *m, const char *dir,
			   int resume, struct stray_error *err);

/*
 * Append one frame: write the FITS file (to name.tmp, fsync, rename,
 * fsync the folder), hash it, then append its manifest row in one write
 * and fsync.  The new row is m->e[m->n - 1].
 */
int stray_sweep_store_append(struct stray_sweep_manifest *m,
			     const struct stray_sweep_frame *f,
			     const struct stray_sweep_image *img,
			     struct stray_error *err);

/* ---- frame reader ------------------------------------------------------ */

struct stray_sweep_header {
	int type;		/* enum stray_sweep_frametyp */
	double angle_deg, exptime_s, ndtrans;
	double monitor;		/* MONITOR, 1 when absent */
	int has_monitor;
	double angle_rb_deg;	/* ANGLERB, ANGLE when absent */
	int has_angle_rb;
	long seqnum, col0, row0, satlevel;
	size_t n_rows, n_cols;	/* NAXIS2, NAXIS1 */
	int has_rows;		/* ROWS present (row-sampled frame) */
	long det_row[STRAY_SWEEP_ROWS_MAX];	/* detector row of each row */
};

struct stray_sweep_fits {
	void *fptr;		/* fitsfile *, opaque here */
	const char *path;
	struct stray_sweep_header h;
	/* An in-memory file: cfitsio keeps the addresses of these two. */
	void *mem;
	size_t mem_size;
	int mem_borrowed;	/* mem is the caller's: not freed */
	size_t data_len;	/* bytes of the file in mem */
	int bitpix, equiv_bitpix;
	int flight;		/* opened as a flight frame: no lab keyword */
};

/* Open and read the header; errors name the file and the keyword.  The
 * file is read whole by stray_sweep_file_load (cfitsio never parses the
 * path), NAXIS1 x NAXIS2 held to its bytes (stray/sizes.h) here as in
 * the other opens. */
int stray_sweep_fits_open(const char *path, struct stray_sweep_fits *f,
			  struct stray_error *err);

/* Open an in-memory FITS image (the fuzz target's entry). */
int stray_sweep_fits_open_mem(const char *name, const void *data,
			      size_t len, struct stray_sweep_fits *f,
			      struct stray_error *err);

/* Open the file read whole into b (stray_sweep_file_load), without a
 * copy: b must outlive the open file. */
int stray_sweep_fits_open_buf(const char *name, struct stray_sweep_buf *b,
			      struct stray_sweep_fits *f,
			      struct stray_error *err);

/* As stray_sweep_fits_open_buf for a frame as a camera in orbit writes
 * it (issue 24): FRAMETYP (FULL when absent), ANGLE (0), NDTRANS (1),
 * SEQNUM (0) and SATLEVEL (65535) are optional; EXPTIME and the image
 * rules are those of the lab frame. */
int stray_sweep_fits_open_flight_buf(const char *name,
				     struct stray_sweep_buf *b,
				     struct stray_sweep_fits *f,
				     struct stray_error *err);

/* Read all n_rows * n_cols pixels into pix (row-major). */
int stray_sweep_fits_read(struct stray_sweep_fits *f, uint16_t *pix,
			  struct stray_error *err);

void stray_sweep_fits_close(struct stray_sweep_fits *f);

/* Parse a ROWS value "960,961,..." into n detector rows. */
int stray_sweep_rows_parse(const char *path, const char *text, long *rows,
			   size_t n, struct stray_error *err);

#endif /* STRAY_SWEEP_STORE_H */
