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

struct frame_rng {
	uint64_t s;
	double spare;		/* second normal of the polar pair */
	int has_spare;
	/* PTRS constants of the last mean (frames repeat it). */
	double lam, slam, loglam, a, b, inv_alpha, vr;
};

void frame_rng_init(struct frame_rng *r, uint64_t seed);
uint64_t frame_rng_next(struct frame_rng *r);
double frame_rng_uniform(struct frame_rng *r);	/* (0, 1) */
double frame_rng_normal(struct frame_rng *r);
double frame_rng_poisson(struct frame_rng *r, double mean);

#endif /* STRAY_FRAMES_RNG_H */
