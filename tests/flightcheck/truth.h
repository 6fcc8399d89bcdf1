/*
 * truth.h - flight frames for the hidden-effect test and the demo (issue
 * 18): frames rendered by libstray/frames along an attitude sweep of the
 * Sun offset angle, the catalogue's stars through the *true* attitude
 * (the AEM written carries a small pointing error, as a real one does),
 * stray light from a truth curve times a hidden scale.  Kept apart from
 * the analysis (mission/flightcheck.c), which reads only the frames'
 * DATE-OBS and the AEM; the truth keywords (TALPHA, TSCALE) are for
 * people.
 */
#ifndef TESTS_FLIGHTCHECK_TRUTH_H
#define TESTS_FLIGHTCHECK_TRUTH_H

#include <stdint.h>

#include "stray/curve.h"
#include "stray/error.h"
#include "stray/starcat.h"

struct fc_truth {
	struct stray_curve_view curve;	/* alpha_sys(theta), truth */
	double scale;		/* hidden: stray = scale k_px alpha F t A_px */
	int n_frames, window;	/* window 0: full frames */
	double theta_lo_deg, theta_hi_deg;
	double mag_max;		/* stars rendered (10) */
	double point_err_arcsec;	/* AEM knowledge error, rms per axis */
	double gradient, hot_frac;	/* truth-only effects of frames.h */
	uint64_t seed;
	/* the real sky (issue 24): a catalogue (NULL: the synthetic sky),
	 * rendered at each frame's epoch with the stars' colours; the
	 * frames' times then written as TIMESYS = TT, DATE-BEG, DATE-END */
	const struct stray_starcat *cat;
	int mixed_exposure;	/* EXPTIME cycles 1, 0.5, 2 x the sensor's */
	double gain_e_per_dn, bias_dn;	/* written as GAIN, BIAS */
};

void fc_truth_defaults(struct fc_truth *t);

/* Write the frames (a sweep folder, dir must not exist) and the AEM. */
int fc_truth_write(const struct fc_truth *t, const char *dir,
		   const char *aem_path, struct stray_error *err);

#endif /* TESTS_FLIGHTCHECK_TRUTH_H */
