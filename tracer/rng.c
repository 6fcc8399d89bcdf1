/*
 * rng.c - Philox4x32-10 (Salmon et al. 2011, SC'11) as a per-path stream:
 * counter = (block, path lo, path hi, 0), key = seed.
 */
#include "tracer/rng.h"

#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u
#define PHILOX_W1 0xBB67AE85u
#define PHILOX_ROUNDS 10

static void mulhilo(uint32_t a, uint32_t b, uint32_t *hi, uint32_t *lo)
{
	uint64_t p = (uint64_t)a * b;

	*hi = (uint32_t)(p >> 32);
	*lo = (uint32_t)p;
}

void tracer_philox4x32(const uint32_t ctr[4], const uint32_t key[2],
		       uint32_t out[4])
{
	uint32_t c[4] = { ctr[0], ctr[1], ctr[2], ctr[3] };
	uint32_t k0 = key[0], k1 = key[1];
	int i;

	for (i = 0; i < PHILOX_ROUNDS; i++) {
		uint32_t hi0, lo0, hi1, lo1;

		mulhilo(PHILOX_M0, c[0], &hi0, &lo0);
		mulhilo(PHILOX_M1, c[2], &hi1, &lo1);
		c[0] = hi1 ^ c[1] ^ k0;
		c[1] = lo1;
		c[2] = hi0 ^ c[3] ^ k1;
		c[3] = lo0;
		k0 += PHILOX_W0;
		k1 += PHILOX_W1;
	}
	out[0] = c[0];
	out[1] = c[1];
	out[2] = c[2];
	out[3] = c[3];
}

void tracer_rng_init(struct tracer_rng *r, uint64_t seed, uint64_t path)
{
	r->seed = seed;
	r->path = path;
	r->counter = 0;
	r->used = 4;
}

double tracer_rng_uniform(struct tracer_rng *r)
{
	if (r->used == 4) {
		uint32_t ctr[4] = { r->counter, (uint32_t)r->path,
				    (uint32_t)(r->path >> 32), 0 };
		uint32_t key[2] = { (uint32_t)r->seed,
				    (uint32_t)(r->seed >> 32) };

		tracer_philox4x32(ctr, key, r->block);
		r->counter++;
		r->used = 0;
	}
	return r->block[r->used++] * (1.0 / 4294967296.0);
}
