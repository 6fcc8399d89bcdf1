/*
 * oem_cov.h - the covariance blocks of an OEM (502.0-B-3 §5.2.5), read
 * and checked by oem.c's reader (private to libstray/host).
 */
#ifndef STRAY_OEM_COV_H
#define STRAY_OEM_COV_H

#include "stray/ccsds.h"

struct oem_cov {
	int row;		/* rows of the current matrix read, 0..6 */
	int have_epoch;		/* an EPOCH opened the current matrix */
	size_t n;		/* complete matrices */
	double c[6][6];
};

/*
 * One line inside COVARIANCE_START .. COVARIANCE_STOP (the STOP word
 * and an unclosed block are oem.c's): EPOCH, COV_REF_FRAME, then six
 * rows of 1..6 numbers, lower triangle; a finished matrix must have a
 * non-negative diagonal and correlations within [-1, 1].  Returns
 * STRAY_OK or STRAY_EPARSE with err set (file, line, field, value).
 */
int oem_cov_line(struct oem_cov *cv, const struct stray_kvn_line *l,
		 int ts, const char *file, long line,
		 struct stray_error *err);

/* At COVARIANCE_STOP: STRAY_EPARSE when a matrix is left short. */
int oem_cov_stop(struct oem_cov *cv, const char *file, long line,
		 struct stray_error *err);

#endif /* STRAY_OEM_COV_H */
