/*
 * pixel_sums.h - how the reduction sums over a full frame (private to
 * libstray/reduce).
 *
 * Lanes: sums over a full frame's pixels in STRAY_LANES independent
 * partial sums (pixel i into lane i % STRAY_LANES), added in lane order
 * at the end.  One running double sum is a chain of dependent additions,
 * bound by the adder's latency (~4 cycles a pixel, 20 M cycles a frame);
 * eight chains run at the adder's throughput and vectorise, and the
 * order stays fixed, so a result does not depend on the machine.
 */
#ifndef STRAY_REDUCE_PIXEL_SUMS_H
#define STRAY_REDUCE_PIXEL_SUMS_H

#include <stddef.h>
#include <stdint.h>

#define STRAY_LANES 8

/* A hot loop built twice, for AVX2 and for the baseline x86-64, the CPU's
 * chosen when the program loads (GCC's function multi-versioning). */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define STRAY_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define STRAY_VECTOR_CLONES
#endif

static inline double stray_lanes_total(const double *lane)
{
	double s = 0.0;
	int k;

	for (k = 0; k < STRAY_LANES; k++)
		s += lane[k];
	return s;
}

/* The mask of a frame without one: every pixel STRAY_PIX_OK (0). */
#define STRAY_PIECE_MAX 4096
extern const uint8_t stray_all_ok[STRAY_PIECE_MAX];

/* The mask over pixels [i, i + *len), *len cut to STRAY_PIECE_MAX (a
 * multiple of 4 and of STRAY_LANES, so column phases and lanes stay the
 * same piece to piece): mask's own, or without one stray_all_ok. */
static inline const uint8_t *stray_mask_piece(const uint8_t *mask, size_t i,
					      size_t *len)
{
	if (*len > STRAY_PIECE_MAX)
		*len = STRAY_PIECE_MAX;
	return mask ? mask + i : stray_all_ok;
}

#endif /* STRAY_REDUCE_PIXEL_SUMS_H */
