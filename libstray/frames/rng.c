/*
 * rng.c - random deviates for the frame renderer (rng.h).
 */
#include <math.h>

#include "rng.h"

void stray_frame_rng_init(struct stray_frame_rng *r, uint64_t seed)
{
	r->s = seed;
	r->has_spare = 0;
	r->lam = -1.0;
}

uint64_t stray_frame_rng_next(struct stray_frame_rng *r)
{
	uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);

	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

double stray_frame_rng_uniform(struct stray_frame_rng *r)
{
	return ((double)(stray_frame_rng_next(r) >> 11) + 0.5) *
	       (1.0 / 9007199254740992.0);
}

double stray_frame_rng_normal(struct stray_frame_rng *r)
{
	double u, v, s, f;

	if (r->has_spare) {
		r->has_spare = 0;
		return r->spare;
	}
	do {
		u = 2.0 * stray_frame_rng_uniform(r) - 1.0;
		v = 2.0 * stray_frame_rng_uniform(r) - 1.0;
		s = u * u + v * v;
	} while (s >= 1.0 || s == 0.0);
	f = sqrt(-2.0 * log(s) / s);
	r->spare = v * f;
	r->has_spare = 1;
	return u * f;
}

/* Inversion by sequential search: means below 10. */
static double poisson_small(struct stray_frame_rng *r, double mean)
{
	double u = stray_frame_rng_uniform(r), p = exp(-mean), c = p;
	int k = 0;

	while (u > c && k < 200) {
		k++;
		p *= mean / k;
		c += p;
	}
	return k;
}

static void ptrs_setup(struct stray_frame_rng *r, double lam)
{
	r->lam = lam;
	r->slam = sqrt(lam);
	r->loglam = log(lam);
	r->b = 0.931 + 2.53 * r->slam;
	r->a = -0.059 + 0.02483 * r->b;
	r->inv_alpha = 1.1239 + 1.1328 / (r->b - 3.4);
	r->vr = 0.9277 - 3.6224 / (r->b - 2.0);
}

double stray_frame_rng_poisson(struct stray_frame_rng *r, double mean)
{
	int it;

	if (!(mean > 0.0))
		return 0.0;
	if (mean < 10.0)
		return poisson_small(r, mean);
	if (mean != r->lam)
		ptrs_setup(r, mean);
	for (it = 0; it < 1000; it++) {
		double u = stray_frame_rng_uniform(r) - 0.5;
		double v = stray_frame_rng_uniform(r);
		double us = 0.5 - fabs(u);
		double k = floor((2.0 * r->a / us + r->b) * u + r->lam + 0.43);

		if (us >= 0.07 && v <= r->vr)
			return k;	/* the squeeze: most draws end here */
		if (k < 0.0 || (us < 0.013 && v > us))
			continue;
		if (log(v) + log(r->inv_alpha) - log(r->a / (us * us) + r->b)
		    <= -r->lam + k * r->loglam - lgamma(k + 1.0))
			return k;
	}
	return floor(mean + 0.5);	/* unreachable in practice */
}
