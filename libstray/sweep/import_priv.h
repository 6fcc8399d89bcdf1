/*
 * import_priv.h - what the files of the sweep import share and no caller
 * sees.
 */
#ifndef STRAY_IMPORT_PRIV_H
#define STRAY_IMPORT_PRIV_H

#include <stdint.h>

#include "stray/sweep_import.h"

/* A TIFF read whole into b (import_tiff.c), as stray_import_frame_read. */
int stray_import_tiff_read(const char *path, const struct stray_sweep_buf *b,
			   struct stray_import_header *h, uint16_t **px,
			   struct stray_error *err);

#define STRAY_IMPORT_PATH_LEN (STRAY_SWEEP_DIR_MAX + STRAY_SWEEP_FILE_MAX + 2)

/* A file given, and the log row naming it. */
struct stray_import_input {
	char path[STRAY_IMPORT_PATH_LEN];
	const char *base;		/* its file name, in path */
	const struct stray_import_row *row;	/* NULL: not in the log */
	char sha[STRAY_SWEEP_SHA256_HEX];	/* of its bytes when checked */
};

/* Write the checked import (import_write.c): row i of log from file
 * of_row[i] with read-back rb[i] (NAN: none) and SEQNUM seq[i]; first
 * is the first frame's header (the sweep's geometry). */
int stray_import_write(const struct stray_import_opts *o,
		       const struct stray_import_log *log,
		       struct stray_import_input *const *of_row,
		       const double *rb, const long *seq,
		       const struct stray_import_header *first,
		       struct stray_import_result *res,
		       struct stray_error *err);

/* The comparisons of import_check.c and their count. */
struct stray_import_check {
	const char *log_name;
	double rotator_zero_deg;
	void (*mismatch)(void *ctx, const struct stray_error *e);
	void *ctx;
	size_t n_mismatch;
	char reason[STRAY_ERROR_FILE_MAX + 192];
};

/* A log row whose file was not given; a file given with no row. */
void stray_import_missing(struct stray_import_check *c,
			  const struct stray_import_row *row);
void stray_import_unlogged(struct stray_import_check *c, const char *path);

/* Header h of the frame (named frame) against its row: every
 * disagreement reported; *rb = the read-back angle (the log's, else
 * ROTATANG's in the log's zero, else NAN). */
void stray_import_check_row(struct stray_import_check *c,
			    const struct stray_import_row *row,
			    const struct stray_import_header *h,
			    const char *frame, double *rb);

/* Geometry, origin, saturation, camera and its settings of h (at path)
 * equal to those of the first frame a (named first), else refused. */
int stray_import_check_same(const struct stray_import_header *a,
			    const char *first,
			    const struct stray_import_header *h,
			    const char *path, struct stray_error *err);

#endif /* STRAY_IMPORT_PRIV_H */
