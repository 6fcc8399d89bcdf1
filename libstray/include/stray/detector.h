/*
 * detector.h - named star detectors and both ways stray light blinds a
 * tracker with each (issue 28; ../shared/docs/method.md §2, §8).
 * Freestanding C99, no heap, every loop bounded.
 *
 * A detector has two failure modes under a background of I_px stray
 * photons per pixel (eq. 2.3):
 *   - false stars: noise crossing its threshold (eq. 2.17-2.18 and their
 *     extensions in fdr_field.h), per image;
 *   - lost stars: a real star of I photons (eq. 2.12) no longer crossing
 *     it, so the designed reference star (DRS) and the stars a solution
 *     needs go missing.
 * Detectors (thresholds set for a dark sky from the DRS, eq. 2.16, except
 * the k sigma one, which follows the frame):
 *   THESIS    eq. 2.18 as published: n_tot/n_pps independent windows; its
 *             lost-star model is eq. 2.16 with the background's variance.
 *   WINDOW    the n_pps disk window summed at every pixel against I_sdt,
 *             one star per connected region (fdr_field.h's sliding model);
 *             a star is found where any window near it clears I_sdt.
 *   THRESHOLD pixels above a fixed threshold (the DRS's min_px-th
 *             brightest pixel at Pr_drs), >= min_px 8-connected.
 *   TETRA3    tetra3 / cedar-solve's get_centroids_from_image defaults:
 *             local-mean background, threshold k times the frame's RMS,
 *             binary opening with the 3x3 cross, then blob areas >= min_px:
 *             constant-false-alarm, so the threshold rises with I_px.
 */
#ifndef STRAY_DETECTOR_H
#define STRAY_DETECTOR_H

#include "stray/detector_blob.h"
#include "stray/detector_pixel.h"
#include "stray/detector_star.h"
#include "stray/detector_types.h"
#include "stray/error.h"

/* "thesis", "window", "threshold", "tetra3" (NULL outside the enum). */
const char *stray_detector_name(enum stray_detector_kind k);

/* The kind named by name; STRAY_EINVAL (field "detector") otherwise. */
int stray_detector_parse(const char *name, enum stray_detector_kind *k,
			 struct stray_error *err);

/*
 * Defaults for a window of n_pps pixels: radius round(sqrt(n_pps / pi)),
 * PSF sigma radius / 4 (the window holds > 99.9 % of a star, as eq. 2.12
 * assumes; stray frames renders the same), min_px 5 and k = 3 (tetra3's
 * minimum area, the sigma issue 28 measured cedar-solve at).
 */
void stray_detector_init(struct stray_detector *d,
			 enum stray_detector_kind kind, stray_real n_pps);

/* Check the parameters and derive the thresholds from the model. */
int stray_detector_setup(struct stray_detector *d,
			 const struct stray_fdr_model *m,
			 struct stray_error *err);

/* ln false stars per image of m->n_tot pixels at alpha (map included,
 * and the background-error term: eq. R of detector.c). */
int stray_detector_log_false_rate(const struct stray_detector *d,
				  const struct stray_fdr_model *m,
				  stray_real alpha, stray_real *log_rate,
				  struct stray_error *err);

enum stray_failure_mode {
	STRAY_FAIL_FALSE_STARS = 0,
	STRAY_FAIL_LOST_STARS = 1
};

/* "false_stars" or "lost_stars". */
const char *stray_failure_mode_name(enum stray_failure_mode f);

struct stray_detector_req {
	stray_real alpha_false;	/* false stars reach the tolerated rate;
				 * +inf: never (a k sigma detector) */
	stray_real alpha_lost;	/* the DRS's detection falls to pr_min;
				 * 0: not even in the dark */
	stray_real alpha_req;	/* the smaller: both requirements met */
	enum stray_failure_mode binding;
};

/*
 * The attenuation below which the detector sees at most `rate` false
 * stars per image and detects the DRS with probability >= pr_min.  The
 * THESIS detector is eq. 2.18 as published: its answer is the false-star
 * one (its I_sdt detects the DRS with exactly Pr_drs in the dark, so
 * alpha_lost is 0 for pr_min = Pr_drs), alpha_lost is reported beside it.
 * STRAY_ERANGE when neither mode is reached; STRAY_EINVAL (pr_drs) when
 * the DRS is missed with pr_min even in the dark.
 */
int stray_detector_alpha_required(const struct stray_detector *d,
				  const struct stray_fdr_model *m,
				  stray_real rate, stray_real pr_min,
				  struct stray_detector_req *r,
				  struct stray_error *err);

#endif /* STRAY_DETECTOR_H */
