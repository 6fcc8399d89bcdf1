/*
 * import_check.c - a foreign frame's header against its log row, and
 * against the sweep's first frame (sweep_import.h).  Log and header
 * disagreeing is a mismatch, reported with the log's file and line and
 * the frame's name, all of them before anything is refused; a camera
 * setting changing inside the sweep is refused at once (the reduction
 * assumes one detector response).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "import_priv.h"
#include "stray/errfmt.h"

/* Tolerances of the comparisons (docs/limits.md). */
#define EXP_REL 1e-3		/* 0.1 %: a log written to 4 digits passes,
				 * a wrong exposure (or ND) never does */
#define EXP_ABS 1e-6		/* s: INDI writes EXPTIME to 6 decimals */
#define RB_TOL 0.005		/* deg: ROTATANG to 2-3 decimals */
#define RB_FAR 1.0		/* deg: read-back this far off is another zero */
#define DATE_TOL 1.0		/* s: the log's clock is not the camera's */

static void report(struct stray_import_check *c, const char *col,
		   const char *value, struct stray_error *tmp)
{
	c->n_mismatch++;
	if (c->n_mismatch > STRAY_IMPORT_MISMATCH_MAX || !c->mismatch)
		return;
	stray_error_column(tmp, col);
	stray_error_text(tmp, value);
	c->mismatch(c->ctx, tmp);
}

/* One mismatch at the row's line, the frame named in the reason (kept
 * in the check's buffer: the record holds a pointer, used before the
 * next mismatch). */
static void mismatch(struct stray_import_check *c,
		     const struct stray_import_row *row, const char *col,
		     const char *value, const char *what, const char *frame)
{
	struct stray_error e;

	snprintf(c->reason, sizeof(c->reason), "%s in %s", what, frame);
	stray_error_clear(&e);
	stray_error_at(&e, STRAY_EINVAL, c->log_name, row->line, NULL,
		       c->reason);
	report(c, col, value, &e);
}

void stray_import_missing(struct stray_import_check *c,
			  const struct stray_import_row *row)
{
	struct stray_error e;

	stray_error_clear(&e);
	stray_error_at(&e, STRAY_ENOTFOUND, c->log_name, row->line, NULL,
		       "is in the log but not among the files given");
	report(c, STRAY_IMPORT_COL_FILE, row->file, &e);
}

void stray_import_unlogged(struct stray_import_check *c, const char *path)
{
	struct stray_error e;

	snprintf(c->reason, sizeof(c->reason), "is not in the log %s: every "
		 "frame needs its row (angle, type, exposure, ND)",
		 c->log_name);
	stray_error_clear(&e);
	stray_error_at(&e, STRAY_EINVAL, path, 0, NULL, c->reason);
	report(c, "file", strrchr(path, '/') ? strrchr(path, '/') + 1 : path,
	       &e);
}

/* The read-back angle in the log's zero: ROTATANG - zero, in -180..180. */
static double rotator(const struct stray_import_check *c, double rotatang)
{
	double a = fmod(rotatang - c->rotator_zero_deg, 360.0);

	if (a > 180.0)
		a -= 360.0;
	else if (a < -180.0)
		a += 360.0;
	return a;
}

static void check_type(struct stray_import_check *c,
		       const struct stray_import_row *row,
		       const struct stray_import_header *h, const char *frame)
{
	char what[160];
	int log_light = row->type != STRAY_SWEEP_DARK;

	if (h->light < 0 || h->light == log_light)
		return;
	snprintf(what, sizeof(what), "disagrees with the header's %s frame "
		 "('%s')", h->light ? "light" : "dark", h->imagetyp);
	mismatch(c, row, STRAY_IMPORT_COL_TYPE,
		 stray_sweep_frametyp_name(row->type), what, frame);
}

static void check_angles(struct stray_import_check *c,
			 const struct stray_import_row *row,
			 const struct stray_import_header *h,
			 const char *frame, double *rb)
{
	char v[32], what[128];

	*rb = row->readback_deg;
	if (!isnan(*rb) && fabs(*rb - row->angle_deg) > RB_FAR) {
		snprintf(v, sizeof(v), "%.6g", *rb);
		snprintf(what, sizeof(what), "is more than %g deg from the "
			 "logged angle_deg %g", RB_FAR, row->angle_deg);
		mismatch(c, row, STRAY_IMPORT_COL_READBACK, v, what, "the log");
	}
	if (!h->has_rotatang)
		return;
	if (isnan(*rb)) {
		*rb = rotator(c, h->rotatang_deg);
		snprintf(v, sizeof(v), "%.6g", row->angle_deg);
		snprintf(what, sizeof(what), "is more than %g deg from the "
			 "header's read-back ROTATANG %g (another zero? see "
			 "--rotator-zero)", RB_FAR, h->rotatang_deg);
		if (fabs(*rb - row->angle_deg) > RB_FAR)
			mismatch(c, row, STRAY_IMPORT_COL_ANGLE, v, what,
				 frame);
	} else if (fabs(*rb - rotator(c, h->rotatang_deg)) > RB_TOL) {
		snprintf(v, sizeof(v), "%.6g", *rb);
		snprintf(what, sizeof(what), "differs from the header's "
			 "ROTATANG %g by more than %g deg", h->rotatang_deg,
			 RB_TOL);
		mismatch(c, row, STRAY_IMPORT_COL_READBACK, v, what, frame);
	}
}

void stray_import_check_row(struct stray_import_check *c,
			    const struct stray_import_row *row,
			    const struct stray_import_header *h,
			    const char *frame, double *rb)
{
	char v[32], what[160];

	if (h->has_exptime && fabs(h->exptime_s - row->exptime_s) >
	    fmax(EXP_ABS, EXP_REL * h->exptime_s)) {
		snprintf(v, sizeof(v), "%.9g", row->exptime_s);
		snprintf(what, sizeof(what), "differs from the header's "
			 "exposure %.9g s", h->exptime_s);
		mismatch(c, row, STRAY_IMPORT_COL_EXPTIME, v, what, frame);
	}
	check_type(c, row, h, frame);
	if (row->filter[0] && h->format == STRAY_IMPORT_FITS &&
	    strcmp(row->filter, h->filter) != 0) {
		snprintf(what, sizeof(what), "differs from the header's "
			 "FILTER '%s'", h->filter);
		mismatch(c, row, STRAY_IMPORT_COL_FILTER, row->filter, what,
			 frame);
	}
	if (!isnan(row->date_obs) && h->has_date &&
	    fabs(row->date_obs - h->date_obs) > DATE_TOL) {
		stray_sweep_utc_format(row->date_obs, v, sizeof(v));
		snprintf(what, sizeof(what), "is %.3f s from the header's "
			 "DATE-OBS", row->date_obs - h->date_obs);
		mismatch(c, row, STRAY_IMPORT_COL_DATE, v, what, frame);
	}
	check_angles(c, row, h, frame, rb);
}

static int differs(const char *path, const char *key, const char *first,
		   const char *text, struct stray_error *err)
{
	static char reason[STRAY_ERROR_FILE_MAX + 64];

	snprintf(reason, sizeof(reason), "differs from the sweep's first "
		 "frame %s: one camera and one setting per sweep", first);
	stray_error_at(err, STRAY_EINVAL, path, 0, key, reason);
	stray_error_text(err, text);
	return STRAY_EINVAL;
}

int stray_import_check_same(const struct stray_import_header *a,
			    const char *first,
			    const struct stray_import_header *h,
			    const char *path, struct stray_error *err)
{
	char t[64];
	int k;

	if (h->format != a->format)
		return differs(path, "file", first, h->format ==
			       STRAY_IMPORT_FITS ? "FITS" : "TIFF", err);
	snprintf(t, sizeof(t), "%zu x %zu", h->n_cols, h->n_rows);
	if (h->n_rows != a->n_rows || h->n_cols != a->n_cols)
		return differs(path, "NAXIS1 x NAXIS2", first, t, err);
	snprintf(t, sizeof(t), "%ld,%ld", h->col0, h->row0);
	if (h->has_origin != a->has_origin || h->col0 != a->col0 ||
	    h->row0 != a->row0)
		return differs(path, "XORGSUBF,YORGSUBF", first, t, err);
	snprintf(t, sizeof(t), "%ld", h->satlevel);
	if (h->has_satlevel != a->has_satlevel || h->satlevel != a->satlevel)
		return differs(path, "SATURATE", first, t, err);
	if (strcmp(h->instrume, a->instrume) != 0)
		return differs(path, "INSTRUME", first, h->instrume, err);
	/* CCD-TEMP (the last) drifts and is only kept */
	for (k = 0; k < STRAY_IMPORT_SETTINGS - 1; k++) {
		snprintf(t, sizeof(t), "%.9g", h->setting[k]);
		if (h->has_setting[k] != a->has_setting[k] ||
		    (h->has_setting[k] && h->setting[k] != a->setting[k]))
			return differs(path, stray_import_setting_key(k), first,
				       h->has_setting[k] ? t : "(absent)",
				       err);
	}
	return STRAY_OK;
}
