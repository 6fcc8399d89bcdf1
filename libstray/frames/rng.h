/*
 * rng.h - the random numbers of the frame renderer (private): splitmix64
 * (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number
 * generators", OOPSLA), uniform doubles, normal pairs (Marsaglia's polar
 * method) and Poisson deviates (Hoermann 1993, "The transformed
 * rejection method for generating Poisson random variables", Insurance:
 * Mathematics and Economics 12, 39: PTRS, mean >= 10; inversion below).
 */
#ifndef STRAY_FRAMES_RNG_H
#define STRAY_FRAMES_RNG_H

#include <stdint.h>

struct stray_frame_rng {
	uint64_t s;
	double spare;		/* second normal of the polar pair */
	int has_spare;
	/* PTRS constants of the last mean (frames repeat it). */
	double lam, slam, loglam, a, b, inv_alpha, vr;
};

void stray_frame_rng_init(struct stray_frame_rng *r, uint64_t seed);
uint64_t stray_frame_rng_next(struct stray_frame_rng *r);
double stray_frame_rng_uniform(struct stray_frame_rng *r);	/* (0, 1) */
double stray_frame_rng_normal(struct stray_frame_rng *r);
double stray_frame_rng_poisson(struct stray_frame_rng *r, double mean);

#endif /* STRAY_FRAMES_RNG_H */
