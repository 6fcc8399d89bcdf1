/*
 * rng.h - counter-based random numbers (Philox4x32-10: Salmon, Moraes,
 * Dror, Shaw 2011, "Parallel random numbers: as easy as 1, 2, 3", SC'11,
 * doi:10.1145/2063384.2063405).  A path's numbers are a pure function of
 * (seed, path index, draw counter), so results do not depend on which
 * thread traced the path or in which order.
 */
#ifndef TRACER_RNG_H
#define TRACER_RNG_H

#include <stdint.h>

struct tracer_rng {
	uint64_t seed;
	uint64_t path;
	uint32_t counter;	/* blocks of four numbers drawn so far */
	uint32_t block[4];
	int used;		/* numbers taken from block */
};

/* Start the stream of one path. */
void tracer_rng_init(struct tracer_rng *r, uint64_t seed, uint64_t path);

/* Uniform in [0, 1), 32 bits of resolution. */
double tracer_rng_uniform(struct tracer_rng *r);

/* The raw Philox4x32-10 block function (exposed for its known-answer test). */
void tracer_philox4x32(const uint32_t ctr[4], const uint32_t key[2],
		       uint32_t out[4]);

#endif /* TRACER_RNG_H */
