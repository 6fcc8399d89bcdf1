/*
 * exclusion_models.h - one curve's Sun exclusion angle under every model
 * the toolkit has (issue 28 item 6): the thesis's eq. 2.18 with its
 * k_px = 1, the same with the consistent k_px (docs/normalisation.md),
 * and each validated detector (window, threshold, tetra3 at k = 3 and 5,
 * docs/detectors.md) with the failure mode that sets its angle.  What
 * `stray exclusion --models` prints and the demo's report tabulates.
 */
#ifndef STRAY_EXCLUSION_MODELS_H
#define STRAY_EXCLUSION_MODELS_H

#include "stray/curve.h"
#include "stray/detector.h"
#include "stray/error.h"
#include "stray/sensor.h"

#define STRAY_EXCL_MODELS 6

struct stray_excl_model {
	const char *model;		/* static: "thesis k_px=1", ... */
	enum stray_detector_kind detector;
	double sigma_k;			/* tetra3's k; 0 for the others */
	double k_px;			/* eq. 2.3's per-pixel factor */
	double alpha_false;		/* false stars reach the rate */
	double alpha_lost;		/* the DRS's detection falls to Pr_drs
					 * (NaN: the thesis's eq. 2.18 has
					 * no such model) */
	double alpha_req;		/* the smaller: what binds */
	enum stray_failure_mode binding;
	int excluded;			/* stray_exclusion_interval's verdict */
	double sun_deg;			/* NaN when not excluded */
	const char *reason;		/* static, when not excluded */
};

/*
 * The STRAY_EXCL_MODELS answers for the Sun (photon flux f_sun; the DRS's
 * f_drs; rate false stars per image tolerated, <= 0: the sensor's) on
 * curve c, in the order above.  The thesis rows are eq. 2.18 as
 * published (Gaussian shot noise, no detector noise); the detectors' have
 * the camera's read noise and dark current, as they are validated.
 */
int stray_exclusion_models(const struct stray_curve_view *c,
			   const struct stray_sensor *s, double f_sun,
			   double f_drs, double rate,
			   struct stray_excl_model out[STRAY_EXCL_MODELS],
			   struct stray_error *err);

#endif /* STRAY_EXCLUSION_MODELS_H */
