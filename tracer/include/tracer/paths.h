/*
 * paths.h - path statistics: detector power per source angle keyed by the
 * sequence of surface groups the light scattered from (thesis §5.3).
 *
 * A recorded value is the path's contribution divided by the product of
 * the reflectance scales (rho) of its scatter vertices, so a caller can
 * re-evaluate any change of per-group reflectance as
 * sum over keys of value * prod rho'(group), without re-tracing (the
 * diagnose fit of thesis §4 varies exactly these).
 */
#ifndef TRACER_PATHS_H
#define TRACER_PATHS_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

/* Groups kept per key; longer paths keep their first ones (source side)
 * and set the TRACER_SEQ_TRUNCATED bit. */
#define TRACER_SEQ_MAX 7
#define TRACER_SEQ_TRUNCATED (1ull << 63)

struct tracer_path_entry {
	uint64_t seq;		/* length in bits 56..59, groups 8 bits each */
	uint32_t theta_index;
	uint32_t used;
	double value;		/* sum of contribution / prod rho, all batches */
	double value_b2;	/* sum over batches of (batch sum)^2 */
	double n_paths;		/* number of connections recorded */
};

struct tracer_path_table {
	size_t cap, n;
	struct tracer_path_entry *e;
};

/* Pack a source-to-detector group sequence (groups[0] lit by the source). */
uint64_t tracer_seq_pack(const int *groups, int n);

/* Length and groups of a key; returns the number of groups written. */
int tracer_seq_unpack(uint64_t seq, int groups[TRACER_SEQ_MAX]);

/* Add v to (theta_index, seq); one call per connection. */
int tracer_paths_add(struct tracer_path_table *t, uint32_t theta_index,
		     uint64_t seq, double v);

/* Merge a batch table into a total, keeping per-batch squares for sigma. */
int tracer_paths_merge(struct tracer_path_table *total,
		       const struct tracer_path_table *batch);

/* Entry for a key, or NULL. */
const struct tracer_path_entry *
tracer_paths_find(const struct tracer_path_table *t, uint32_t theta_index,
		  uint64_t seq);

void tracer_paths_free(struct tracer_path_table *t);

#endif /* TRACER_PATHS_H */
