/*
 * frames_sat.c - refuse or flag frames whose background fills the ADC
 * (frames_sat.h).
 */
#include <math.h>
#include <stdio.h>

#include "frames/frames_sat.h"
#include "stray/frames.h"

/* The background level (e-) above which a pixel's noise tail clips:
 * level + k sqrt(level + read^2) = full scale, solved for level. */
static double clip_level(const struct frames_model *fm)
{
	double full = (STRAY_FRAMES_SAT_DN - STRAY_FRAMES_BIAS_DN) *
		      STRAY_FRAMES_GAIN_E_PER_DN;
	double k = FRAMES_SAT_SIGMAS, r2 = fm->read_noise_e * fm->read_noise_e;
	/* x = sqrt(level + r2): x^2 + k x - (full + r2) = 0 */
	double x = 0.5 * (-k + sqrt(k * k + 4.0 * (full + r2)));

	return x * x - r2;
}

int frames_saturation(const struct frames_model *fm, const float *weight,
		      size_t n, double alpha, double *clip_frac,
		      struct stray_error *err)
{
	double lim = clip_level(fm);
	size_t i, clip = 0;

	if (!weight)
		clip = fm->stray_e + fm->dark_e >= lim ? n : 0;
	else
		for (i = 0; i < n; i++)
			clip += fm->stray_e * weight[i] + fm->dark_e >= lim;
	*clip_frac = n ? (double)clip / (double)n : 0.0;
	if (n == 0 || clip < n)
		return STRAY_OK;
	return stray_error_set_value(err, STRAY_EINVAL, "alpha",
		"the stray light fills every pixel to the 12-bit ADC's full scale "
		"(7990 e- within 5 sigma): the frames hold neither stars nor "
		"false stars, no verdict", alpha);
}

int frames_saturation_verdict(double clip_frac, char *text, size_t size)
{
	if (!(clip_frac > FRAMES_SAT_FLAG))
		return 0;
	snprintf(text, size,
		 "no verdict: %.3g %% of the pixels' background lies within 5 sigma "
		 "of the ADC's full scale (clipped pixels have no noise tail and no "
		 "room for stars; the models assume none clip)", 100.0 * clip_frac);
	return 1;
}
