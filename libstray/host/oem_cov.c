/*
 * oem_cov.c - covariance blocks of an OEM, parsed and checked: a block
 * with a row short, a row too many or a correlation above 1 is a broken
 * message, not something to skip.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "oem_cov.h"
#include "stray/errfmt.h"

/* A correlation may exceed 1 by the rounding of the printed digits. */
#define CORR_TOL 1e-6

/* Frames a covariance may be given in: the state frames and the local
 * orbital frames of 502.0-B-3 Annex A. */
static int cov_frame(const char *v)
{
	static const char *const lof[] = { "RTN", "RSW", "RIC", "TNW",
		"QSW", "LVLH", "NSW", "UVW", "VNC" };
	size_t i;

	for (i = 0; i < sizeof(lof) / sizeof(lof[0]); i++)
		if (stray_kvn_eq(v, lof[i]))
			return 1;
	return stray_ccsds_frame(v) >= 0;
}

static int bad(struct stray_error *err, const char *file, long line,
	       const char *key, const char *why, const char *text)
{
	return stray_kvn_fail(err, file, line, key, why, text);
}

static int finish(struct oem_cov *cv, const char *file, long line,
		  struct stray_error *err)
{
	char at[64];
	int i, j;

	for (i = 0; i < 6; i++)
		if (!(cv->c[i][i] >= 0.0)) {
			snprintf(at, sizeof(at), "C(%d,%d) = %g", i + 1, i + 1,
				 cv->c[i][i]);
			return bad(err, file, line, "covariance",
				   "a negative variance", at);
		}
	for (i = 0; i < 6; i++)
		for (j = 0; j < i; j++)
			if (fabs(cv->c[i][j]) > sqrt(cv->c[i][i] * cv->c[j][j]) *
			    (1.0 + CORR_TOL)) {
				snprintf(at, sizeof(at), "C(%d,%d) = %g", i + 1,
					 j + 1, cv->c[i][j]);
				return bad(err, file, line, "covariance",
					   "a correlation beyond 1: not a covariance", at);
			}
	cv->n++;
	return STRAY_OK;
}

int oem_cov_line(struct oem_cov *cv, const struct stray_kvn_line *l,
		 int ts, const char *file, long line,
		 struct stray_error *err)
{
	double t;
	int k, e;

	if (l->kind == STRAY_KVN_KEYVAL) {
		if (strcmp(l->key, "EPOCH") == 0) {
			if (cv->have_epoch && cv->row != 6)
				return oem_cov_stop(cv, file, line, err);
			if ((e = stray_ccsds_epoch(l->value, ts, &t)) != 0)
				return bad(err, file, line, l->key, e == -2 ?
					   "second 60 where no leap second is" :
					   "not a CCSDS epoch YYYY-MM-DDThh:mm:ss", l->value);
			cv->have_epoch = 1;
			cv->row = 0;
			return STRAY_OK;
		}
		if (strcmp(l->key, "COV_REF_FRAME") == 0) {
			if (!cv->have_epoch || cv->row != 0)
				return bad(err, file, line, l->key,
					   "must follow the matrix's EPOCH", l->value);
			if (!cov_frame(l->value))
				return bad(err, file, line, l->key,
					   "not a frame a covariance is given in", l->value);
			return STRAY_OK;
		}
		return bad(err, file, line, l->key,
			   "keyword inside the covariance block", l->key);
	}
	if (!cv->have_epoch)
		return bad(err, file, line, "EPOCH",
			   "missing before the covariance rows", l->field[0]);
	if (cv->row == 6)
		return bad(err, file, line, "covariance",
			   "a 7th row: the matrix is 6x6", l->field[0]);
	if (l->n_field != cv->row + 1) {
		char got[48];

		/* the reason must outlive this call: the count goes in the text */
		snprintf(got, sizeof(got), "row %d of %d numbers", cv->row + 1,
			 l->n_field);
		return bad(err, file, line, "covariance",
			   "row k of the lower triangle holds k numbers", got);
	}
	for (k = 0; k < l->n_field; k++) {
		double x;

		if (!stray_kvn_number(l->field[k], &x))
			return bad(err, file, line, "covariance",
				   "not a number", l->field[k]);
		cv->c[cv->row][k] = cv->c[k][cv->row] = x;
	}
	if (++cv->row == 6)
		return finish(cv, file, line, err);
	return STRAY_OK;
}

int oem_cov_stop(struct oem_cov *cv, const char *file, long line,
		 struct stray_error *err)
{
	char at[40];

	if (!cv->have_epoch || cv->row == 6)
		return STRAY_OK;
	snprintf(at, sizeof(at), "%d of 6 rows", cv->row);
	return bad(err, file, line, "covariance",
		   "the matrix ends short of its 6 rows", at);
}
