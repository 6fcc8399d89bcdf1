/*
 * star_field.c - a synthetic star field with a realistic magnitude
 * distribution (frames.h): no catalogue is shipped (Debian packages one
 * only inside Stellarium's data), so the field is drawn from all-sky
 * average counts and said so in every output that uses it.
 */
#include <math.h>

#include "rng.h"
#include "stray/frames.h"

#define COUNTS_AT_6 0.121	/* stars per deg^2 brighter than m = 6 */
#define COUNTS_SLOPE 0.44	/* d log10 N(<m) / dm */

double stray_star_counts_per_deg2(double mag)
{
	return COUNTS_AT_6 * pow(10.0, COUNTS_SLOPE * (mag - 6.0));
}

/* A Poisson count: the renderer's sampler, or a rounded normal above 30. */
static size_t draw_count(struct stray_frame_rng *r, double mean)
{
	double v;

	if (mean < 30.0)
		return (size_t)stray_frame_rng_poisson(r, mean);
	v = floor(mean + sqrt(mean) * stray_frame_rng_normal(r) + 0.5);
	return v > 0.0 ? (size_t)v : 0;
}

void stray_star_field_draw(const struct stray_star_field *f, int cols,
			   int rows, uint64_t seed, struct stray_star *stars,
			   size_t max, size_t *n)
{
	struct stray_frame_rng r;
	double n_lo = stray_star_counts_per_deg2(f->mag_min);
	double n_hi = stray_star_counts_per_deg2(f->mag_max);
	size_t i, k;

	stray_frame_rng_init(&r, seed ^ 0xA5A5A5A5DEADBEEFull);
	k = draw_count(&r, (n_hi - n_lo) * f->fov_deg2);
	/* A short buffer truncates the draw (i.i.d. stars: a fair subset). */
	if (k > max)
		k = max;
	for (i = 0; i < k; i++) {
		struct stray_star *s = &stars[i];
		double u = stray_frame_rng_uniform(&r), nm = n_lo + u * (n_hi - n_lo);

		s->mag = 6.0 + log10(nm / COUNTS_AT_6) / COUNTS_SLOPE;
		s->x = cols * stray_frame_rng_uniform(&r);
		s->y = rows * stray_frame_rng_uniform(&r);
		s->photons_e = f->f0_e * pow(10.0, -0.4 * s->mag); /* eq. 2.2 */
	}
	*n = k;
}
