/*
 * frames_adc.h - the lost-star models of stray/detector.h for the OpenCV
 * detectors of `stray frames` as each frame sets them (issue 28): the
 * detectors subtract their own tile background b^ (a clipped mean that
 * holds the stars' own light) and compare 12-bit DN, so
 *   - the window sum of n_px pixels sits n_px (b^ - L) below the model's,
 *     L the model's stray + dark level at the star: I_sdt becomes
 *     I_sdt + n_px (b^ - L);
 *   - a pixel's test res > t on DN steps of g e- is the analog test
 *     s > t_eff, t_eff = t + (b^ - L) + g (1/2 - frac((t + b^) / g))    (1)
 *     (DN = round(A / g + bias), bias whole: DN > (t + b^)/g + bias holds
 *     iff A - L >= g (floor((t + b^)/g) + 1/2) - L), so t moves by up to
 *     one step with the background's place on the steps, and the ADC's
 *     g^2/12 leaves the pixel variance (it is now exact, not noise).
 * The found rule of the window detector is the model's: a region of
 * above-threshold window centres reaching within FRAMES_REACH_PX of the
 * star (its centroid may lie farther; counting centroids within the
 * window radius found 0.05-0.08 more stars than the model describes).
 * Measured in tests/frames/test_detect_gap.c.
 */
#ifndef STRAY_FRAMES_FRAMES_ADC_H
#define STRAY_FRAMES_FRAMES_ADC_H

#include "frames/frames_detect.h"
#include "stray/detector.h"

#define FRAMES_REACH_PX 3.0	/* detector_star.c: windows within 3 px */

struct frames_adc {
	const float *tiles;	/* the detector's background per tile, e- */
	int tiles_x, tiles_y, tile_px, cols, rows;
	const float *weight;	/* the known map (mean 1) or NULL */
	double stray_e, dark_e;	/* the model's mean stray, dark e-/px */
	double read_noise_e;	/* the camera's, without the ADC's steps */
	double gain_e_per_dn;
};

/* The detector's background at (x, y) (pixel centres at i + 0.5):
 * bilinear between tile centres, extrapolated, as frames_detect.cpp. */
double frames_adc_bg_at(const struct frames_adc *a, double x, double y);

/* The model's stray + dark level at (x, y). */
double frames_adc_level_at(const struct frames_adc *a, double x, double y);

/* t_eff of (1) for a pixel threshold t_e, background estimate bg_e and
 * level level_e. */
double frames_adc_threshold(double t_e, double bg_e, double level_e,
			    double gain_e_per_dn);

/*
 * The chance that detector d (WINDOW with its I_sdt, THRESHOLD with its
 * pixel threshold, both set up on m) finds a star of star_e at (x, y) of
 * this frame: the local level (m's map left out, alpha_eff times the
 * weight there) and the thresholds above.
 */
int frames_adc_star_prob(const struct frames_adc *a,
			 const struct stray_detector *d,
			 const struct stray_fdr_model *m, double alpha_eff,
			 double x, double y, double star_e, double *p,
			 struct stray_error *err);

/* The window detector found the star at (x, y): a region's bounding box
 * reaches within reach px of it. */
int frames_adc_window_found(const struct frames_detect_out *o, double x,
			    double y, double reach);

#endif /* STRAY_FRAMES_FRAMES_ADC_H */
