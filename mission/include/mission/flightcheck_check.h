/*
 * flightcheck_check.h - `stray flightcheck` as one call: flight frames and
 * the head's AEM against a model curve, the frames calibrated by their
 * catalogue stars, the measured curve's scale against the model and the
 * verdict; and the flight curve as a curve file (for stray diagnose).
 * `stray flightcheck` (tools/cmd_flightcheck.c) prints and plots it.
 */
#ifndef STRAY_MISSION_FLIGHTCHECK_CHECK_H
#define STRAY_MISSION_FLIGHTCHECK_CHECK_H

#include <stddef.h>

#include "mission/flightcheck_run.h"
#include "stray/error.h"
#include "stray/fdr_setup.h"

struct fc_check_opts {
	const char *dir;	/* the frames' folder (or the first file) */
	char *const *files;	/* frame files instead of the folder, or NULL */
	size_t n_files;
	const char *aem;	/* the head's attitude (CCSDS AEM) */
	const char *model;	/* the predicted curve alpha(theta) */
	const char *catalogue;	/* a star catalogue; NULL: the synthetic sky */
	const char *oem;	/* the orbit; NULL: Moon from the Earth's centre */
	double moon_min_deg, limb_min_deg;	/* frames screened out of the fit */
};

struct fc_check {
	struct fc_cfg cfg;
	struct fc_frame *f;	/* per frame, in manifest order */
	struct fc_point *p;	/* the same frames' points, model set */
	size_t n;
	struct fc_summary s;
	char cat_name[64];	/* "synthetic" or "<kind> <file>" */
	char why[256];		/* not empty: the frames cannot be calibrated */
};

/* Analyse the frames of o for the loaded setup su.  STRAY_OK with why
 * set when they cannot be calibrated (no number is to be reported);
 * errors name the file and field.  Free c with fc_check_free. */
int fc_check_run(const struct fc_check_opts *o, const struct fdr_setup *su,
		 struct fc_check *c, struct stray_error *err);

void fc_check_free(struct fc_check *c);

/* The flight curve at path: theta_deg, alpha (alpha_px / k_px of the
 * model), sigma, model; its scale, catalogue and calibration sigma as
 * metadata.  p in the order to write (by angle, as curves are). */
int fc_write_curve(const char *path, const struct fc_point *p, size_t n,
		   const struct fc_summary *s, const char *cat_name,
		   struct stray_error *err);

#endif /* STRAY_MISSION_FLIGHTCHECK_CHECK_H */
