/*
 * paths.c - an open-addressing table of (angle, group sequence) tallies.
 */
#include <stdlib.h>
#include <string.h>

#include "tracer/paths.h"

uint64_t tracer_seq_pack(const int *groups, int n)
{
	uint64_t seq = 0;
	int i, k = n < TRACER_SEQ_MAX ? n : TRACER_SEQ_MAX;

	for (i = 0; i < k; i++)
		seq |= (uint64_t)(groups[i] & 0xff) << (8 * i);
	seq |= (uint64_t)k << 56;
	if (n > TRACER_SEQ_MAX)
		seq |= TRACER_SEQ_TRUNCATED;
	return seq;
}

int tracer_seq_unpack(uint64_t seq, int groups[TRACER_SEQ_MAX])
{
	int i, k = (int)((seq >> 56) & 0xf);

	for (i = 0; i < k && i < TRACER_SEQ_MAX; i++)
		groups[i] = (int)((seq >> (8 * i)) & 0xff);
	return k;
}

static size_t slot_of(uint32_t j, uint64_t seq, size_t cap)
{
	/* splitmix64 finaliser as the hash */
	uint64_t h = seq ^ ((uint64_t)j * 0x9E3779B97F4A7C15ull);

	h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
	h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
	return (size_t)(h ^ (h >> 31)) & (cap - 1);
}

static struct tracer_path_entry *lookup(struct tracer_path_table *t,
					uint32_t j, uint64_t seq)
{
	size_t i = slot_of(j, seq, t->cap);

	while (t->e[i].used &&
	       (t->e[i].seq != seq || t->e[i].theta_index != j))
		i = (i + 1) & (t->cap - 1);
	return &t->e[i];
}

static int grow(struct tracer_path_table *t)
{
	struct tracer_path_table n = { t->cap ? 2 * t->cap : 1024, 0, NULL };
	size_t i;

	n.e = calloc(n.cap, sizeof(*n.e));
	if (!n.e)
		return STRAY_ENOMEM;
	for (i = 0; i < t->cap; i++)
		if (t->e[i].used) {
			*lookup(&n, t->e[i].theta_index, t->e[i].seq) = t->e[i];
			n.n++;
		}
	free(t->e);
	*t = n;
	return STRAY_OK;
}

static struct tracer_path_entry *slot(struct tracer_path_table *t,
				      uint32_t j, uint64_t seq)
{
	struct tracer_path_entry *e;

	if (2 * (t->n + 1) > t->cap && grow(t))
		return NULL;
	e = lookup(t, j, seq);
	if (!e->used) {
		e->used = 1;
		e->seq = seq;
		e->theta_index = j;
		t->n++;
	}
	return e;
}

int tracer_paths_add(struct tracer_path_table *t, uint32_t theta_index,
		     uint64_t seq, double v)
{
	struct tracer_path_entry *e = slot(t, theta_index, seq);

	if (!e)
		return STRAY_ENOMEM;
	e->value += v;
	e->n_paths += 1.0;
	return STRAY_OK;
}

int tracer_paths_merge(struct tracer_path_table *total,
		       const struct tracer_path_table *batch)
{
	size_t i;

	for (i = 0; i < batch->cap; i++) {
		const struct tracer_path_entry *b = &batch->e[i];
		struct tracer_path_entry *e;

		if (!b->used)
			continue;
		e = slot(total, b->theta_index, b->seq);
		if (!e)
			return STRAY_ENOMEM;
		e->value += b->value;
		e->value_b2 += b->value * b->value;
		e->n_paths += b->n_paths;
	}
	return STRAY_OK;
}

const struct tracer_path_entry *
tracer_paths_find(const struct tracer_path_table *t, uint32_t theta_index,
		  uint64_t seq)
{
	size_t i;

	if (!t->cap)
		return NULL;
	i = slot_of(theta_index, seq, t->cap);
	while (t->e[i].used) {
		if (t->e[i].seq == seq && t->e[i].theta_index == theta_index)
			return &t->e[i];
		i = (i + 1) & (t->cap - 1);
	}
	return NULL;
}

void tracer_paths_free(struct tracer_path_table *t)
{
	free(t->e);
	memset(t, 0, sizeof(*t));
}
