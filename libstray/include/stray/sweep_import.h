/*
 * sweep_import.h - frames taken by other software (INDI/EKOS, camera SDKs,
 * 16-bit TIFF) and the lab's CSV log, made into a sweep folder that
 * `stray reduce` reads (issue 26, item 3; docs/sweep-import.md).
 *
 * The log says what the frames cannot: the angle, the frame type (DARK,
 * AMBIENT, FULL), the exposure and the ND transmission of every file.
 * The headers say what the camera did: each one is checked against its
 * log row, and every disagreement is reported with its file and line.
 * The folder written holds our own frames (same pixels, our keywords,
 * stray/sweep_store.h), the originals byte for byte under original/, and
 * import.csv tying each frame to its original and that file's SHA-256.
 * The inputs are only read.
 */
#ifndef STRAY_SWEEP_IMPORT_H
#define STRAY_SWEEP_IMPORT_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"
#include "stray/sweep_store.h"

/* ---- the log ------------------------------------------------------------ */

/* Columns of the log (header line, any order, any case; others ignored;
 * import_log.c lists the other names each may have). */
#define STRAY_IMPORT_COL_FILE "file"
#define STRAY_IMPORT_COL_ANGLE "angle_deg"
#define STRAY_IMPORT_COL_TYPE "frametyp"
#define STRAY_IMPORT_COL_EXPTIME "exptime_s"
#define STRAY_IMPORT_COL_NDTRANS "ndtrans"
/* or, instead of ndtrans, the ND's optical density d (10^-d) */
#define STRAY_IMPORT_COL_ND_OD "nd_od"
/* optional */
#define STRAY_IMPORT_COL_READBACK "readback_deg"
#define STRAY_IMPORT_COL_FILTER "filter"
#define STRAY_IMPORT_COL_DATE "date_obs"
#define STRAY_IMPORT_COL_MONITOR "monitor"

/* Rows a log may have (as the flight folder's files). */
#define STRAY_IMPORT_ROWS_MAX STRAY_SWEEP_FLIGHT_FILES_MAX
#define STRAY_IMPORT_TEXT_MAX 72	/* a FITS string value and its NUL */

struct stray_import_row {
	char file[STRAY_SWEEP_FILE_MAX];	/* a plain file name */
	int type;			/* enum stray_sweep_frametyp */
	double angle_deg, exptime_s, ndtrans;
	double readback_deg;		/* NAN: no read-back logged */
	double date_obs;		/* UTC s; NAN: none logged */
	double monitor;			/* NAN: none logged */
	char filter[STRAY_IMPORT_TEXT_MAX];	/* "" : none logged */
	long line;			/* line in the log */
};

struct stray_import_log {
	size_t n, cap;
	struct stray_import_row *r;
	int has_filter, has_readback, has_date, has_monitor;
};

/*
 * Parse log text (name in messages): '#' lines and blank lines skipped,
 * the first other line the header.  Every value is checked (angle
 * finite in -180..180, exptime > 0, ndtrans in (0, 1], frametyp DARK,
 * AMBIENT or FULL in any case, a file named once); every error names
 * the line and the column.
 */
int stray_import_log_parse(const char *name, const char *text, size_t len,
			   struct stray_import_log *log,
			   struct stray_error *err);
void stray_import_log_free(struct stray_import_log *log);

/* ---- one foreign frame --------------------------------------------------- */

enum stray_import_format { STRAY_IMPORT_FITS, STRAY_IMPORT_TIFF };

/* What a foreign frame's header says, in our terms (has_* 0: absent). */
struct stray_import_header {
	int format;			/* enum stray_import_format */
	size_t n_rows, n_cols;
	int has_exptime;		/* EXPTIME, else EXPOSURE */
	double exptime_s;
	int light;			/* IMAGETYP/FRAME: 1 light, 0 dark,
					 * -1 absent */
	char imagetyp[STRAY_IMPORT_TEXT_MAX];	/* as written */
	char filter[STRAY_IMPORT_TEXT_MAX];	/* FILTER, "" absent */
	int has_rotatang;
	double rotatang_deg;		/* ROTATANG */
	int has_date;
	double date_obs;		/* DATE-OBS, UTC s */
	int has_origin;
	long col0, row0;		/* XORGSUBF, YORGSUBF */
	int has_satlevel;
	long satlevel;			/* SATURATE */
	int bottom_up;			/* ROWORDER = 'BOTTOM-UP' */
	char instrume[STRAY_IMPORT_TEXT_MAX];	/* INSTRUME, "" absent */
	/* camera settings that must not change within a sweep (GAIN,
	 * EGAIN, OFFSET, PEDESTAL) and CCD-TEMP, kept in our frame */
#define STRAY_IMPORT_SETTINGS 5
	int has_setting[STRAY_IMPORT_SETTINGS];
	double setting[STRAY_IMPORT_SETTINGS];
};

/* The keyword of setting k (GAIN, EGAIN, OFFSET, PEDESTAL, CCD-TEMP). */
const char *stray_import_setting_key(int k);

/*
 * Open a foreign frame read whole (bytes b->data, b->len; b from
 * stray_sweep_file_load): FITS (primary HDU, BITPIX 16 with BZERO 32768,
 * NAXIS 2, no binning) or TIFF (one page, one 16-bit unsigned grey
 * sample, strips), by its first bytes.  px (NULL: header only) gets
 * n_rows * n_cols counts, malloc'd, first row the detector's first
 * (a BOTTOM-UP FITS is turned over).  Errors name path and keyword.
 */
int stray_import_frame_read(const char *path, const struct stray_sweep_buf *b,
			    struct stray_import_header *h, uint16_t **px,
			    struct stray_error *err);

/* ---- the import ---------------------------------------------------------- */

struct stray_import_opts {
	const char *log_path;
	const char *out_dir;		/* must not exist, or be empty */
	char *const *inputs;		/* files and folders */
	size_t n_inputs;
	int has_origin;			/* --col0/--row0 given */
	long col0, row0;
	int has_satlevel;		/* --satlevel given */
	long satlevel;
	double rotator_zero_deg;	/* ROTATANG at logged angle 0 */
	/* Called once per mismatch between the log and the frames (each a
	 * one-line error with its file and line); may be NULL. */
	void (*mismatch)(void *ctx, const struct stray_error *e);
	void *ctx;
};

struct stray_import_result {
	size_t n_frames, n_fits, n_tiff;
	size_t n_angles, n_dark, n_ambient, n_full;
	size_t n_rows, n_cols;
	long col0, row0, satlevel;
	size_t n_mismatch;		/* > 0: nothing was written */
	int readback;			/* frames carry ANGLERB */
	int dated;			/* every frame has its DATE-OBS */
	char instrume[STRAY_IMPORT_TEXT_MAX];
};

/* Mismatches reported at most (the count goes on). */
#define STRAY_IMPORT_MISMATCH_MAX 50

/*
 * Check everything, then write the folder (as out_dir.tmp.PID, renamed
 * into place at the end: a refused or failed import leaves nothing).
 * Mismatches between log and headers are all reported through
 * o->mismatch, then refused (STRAY_EINVAL, err naming the count);
 * impossible input is refused at the first error.
 */
int stray_sweep_import(const struct stray_import_opts *o,
		       struct stray_import_result *res,
		       struct stray_error *err);

#endif /* STRAY_SWEEP_IMPORT_H */
