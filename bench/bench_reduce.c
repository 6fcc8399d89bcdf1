/*
 * bench_reduce.c - full-frame (2592 x 1944) reduction throughput beside
 * this machine's memcpy bandwidth measured in the same run: the whole
 * `stray reduce` pipeline (SHA-256, cfitsio, both dark passes, two
 * groups, eq. 3.4-3.14, ghosts) over the sweep's bytes, with and
 * without the hash check, and its two largest per-frame steps alone:
 * the accumulation (eq. 3.4-3.6) and SHA-256.  Those two bound what two
 * cores can reach with the check on.  Every figure is taken in
 * alternating rounds (memcpy, steps, reduce, memcpy, ...; BENCH_PAIRS,
 * bench_alt.h) and printed as the median and min-max of its ratio to
 * the memcpy of the same round.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_alt.h"
#include "stray/reduce_response.h"
#include "stray/sweep_store.h"
#include "synth_sweep.h"
#include "stray/reduce_sweep.h"

#define ROWS 1944
#define COLS 2592
#define ANGLES 4		/* 2 darks, then 3 FULL + 3 AMBIENT a visit */
#define REPEATS 3		/* frames averaged per group (thesis §3.2) */
#define STREAM_BYTES ((size_t)256 << 20)	/* 8x the L3 of this VM */

#define now_s bench_now

/* Best of 5 copies of n bytes, MB/s. */
static double memcpy_mb_s(size_t n)
{
	unsigned char *a = malloc(n), *b = malloc(n);
	double best = 1e30;
	int k;

	memset(a, 1, n);
	memset(b, 2, n);
	for (k = 0; k < 5; k++) {
		double t0 = now_s();

		memcpy(b, a, n);
		a[k] = b[n - 1 - k];
		best = best < now_s() - t0 ? best : now_s() - t0;
	}
	free(a);
	free(b);
	return (double)n / best / 1e6;
}

/* SHA-256 (OpenSSL, as the sweep store checks a frame) of one frame's
 * bytes in memory, best of 5, MB/s. */
static double sha256_mb_s(void)
{
	size_t n = (size_t)ROWS * COLS * 2, i;
	unsigned char *a = malloc(n);
	char hex[STRAY_SWEEP_SHA256_HEX];
	double best = 1e30;
	int k;

	for (i = 0; i < n; i++)
		a[i] = (unsigned char)(i * 2654435761u >> 24);
	for (k = 0; k < 5; k++) {
		double t0 = now_s();

		stray_sweep_sha256_mem(a, n, hex);
		best = best < now_s() - t0 ? best : now_s() - t0;
	}
	free(a);
	return (double)n / best / 1e6;
}

/* The accumulation step on frames in memory, MB of 16-bit counts /s. */
static double accum_mb_s(void)
{
	size_t n = (size_t)ROWS * COLS, i;
	uint16_t *pix = malloc(n * sizeof(*pix));
	long *rows = malloc(ROWS * sizeof(*rows));
	void *mem = malloc(stray_accum_bytes(n));
	struct stray_dark_model *d = calloc(1, sizeof(*d));
	struct stray_bayer_map map;
	struct stray_accum a;
	struct stray_frame f = { ROWS, COLS, pix, rows, 0, 0.1, 1.0, 1.0, 4095 };
	double t0, best = 1e30;
	int k;

	for (i = 0; i < n; i++)
		pix[i] = (uint16_t)(100 + i % 1000);
	for (i = 0; i < ROWS; i++)
		rows[i] = (long)i;
	stray_bayer_default(&map);
	stray_dark_init(d, &map);
	d->n = 1;
	d->lvl[0].t_exp_s = 0.1;
	stray_accum_init(&a, n, mem);
	for (k = 0; k < 5; k++) {
		t0 = now_s();
		stray_accum_add(&a, d, &f, NULL);
		best = best < now_s() - t0 ? best : now_s() - t0;
	}
	free(pix), free(rows), free(mem), free(d);
	return (double)(n * 2) / best / 1e6;
}

/* One `stray reduce` of dir: wall and CPU seconds; 0 or its error. */
static int time_reduce(const char *dir, int verify, double *wall,
		       double *cpu, struct stray_reduce_sweep_result *r)
{
	struct stray_reduce_sweep_opts o;
	struct stray_error err;
	double t0 = now_s();
	clock_t c0 = clock();
	int rc;

	stray_reduce_sweep_opts_default(&o);
	o.verify_sha256 = verify;
	stray_error_clear(&err);
	rc = stray_reduce_sweep(dir, &o, r, &err);
	*wall = now_s() - t0;
	*cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
	return rc;
}

/* MB/s of mb bytes in t[i] seconds, into out[i]. */
static void rates(double mb, const double *t, double *out, int n)
{
	int i;

	for (i = 0; i < n; i++)
		out[i] = mb / t[i];
}

int main(void)
{
	static struct synth_truth truth;
	struct synth_config c;
	struct stray_reduce_sweep_result r;
	char dir[] = "/tmp/stray_bench_XXXXXX", cmd[64];
	double copy[BENCH_MAX_PAIRS], stream[BENCH_MAX_PAIRS];
	double acc[BENCH_MAX_PAIRS], sha[BENCH_MAX_PAIRS];
	double sha2[BENCH_MAX_PAIRS], ceiling[BENCH_MAX_PAIRS];
	double wall[2][BENCH_MAX_PAIRS], cpu[2][BENCH_MAX_PAIRS];
	double v[BENCH_MAX_PAIRS], mb = 0.0, lo, hi;
	int pairs = bench_pairs(), i, k, rc = 0;
	static const char *const what[2] = { "I/O, all passes, --no-verify",
					     "I/O, SHA-256, all passes" };

	if (!mkdtemp(dir))
		return 1;
	synth_default(&c);
	c.n_rows = ROWS;
	c.n_cols = COLS;
	c.n_angles = ANGLES;
	c.revisit = 0;
	c.repeats = REPEATS;
	c.darks_per_exp = 2;
	c.ghosts = 0;
	if (synth_write_sweep(dir, &c, &truth) != 0)
		return 1;
	for (i = 0; i < pairs; i++) {
		copy[i] = memcpy_mb_s((size_t)ROWS * COLS * 2);
		stream[i] = memcpy_mb_s(STREAM_BYTES);
		acc[i] = accum_mb_s();
		sha[i] = sha256_mb_s();
		sha2[i] = 2.0 * sha[i];
		/* every frame hashed and accumulated, nothing else, the
		 * two spread perfectly over 2 cores */
		ceiling[i] = 2.0 / (1.0 / sha[i] + 1.0 / acc[i]);
		for (k = 1; k >= 0; k--) {
			if (i || k == 0)
				stray_reduce_sweep_result_free(&r);
			rc |= time_reduce(dir, k, &wall[k][i], &cpu[k][i], &r);
		}
		/* the sweep's bytes, each frame counted once (its 16-bit
		 * pixels): the darks pass 2 needs come from memory */
		mb = (double)r.n_frames * ROWS * COLS * 2 / 1e6;
	}
	for (i = 0; i < pairs; i++)
		v[i] = copy[i];
	printf("memcpy of one frame (baseline): %.0f MB/s; the rest as x "
	       "memcpy,\nmedian (min-max) of %d alternating rounds:\n",
	       bench_median(v, pairs, &lo, &hi), pairs);
	bench_ratio("memcpy of 256 MB (past the caches):       ", stream,
		    copy, pairs, 7, 3);
	bench_ratio("accumulate one frame (eq. 3.4-3.6):       ", acc, copy,
		    pairs, 7, 3);
	bench_ratio("SHA-256 of one frame (OpenSSL):           ", sha, copy,
		    pairs, 7, 3);
	bench_ratio("  the hash alone on both cores:           ", sha2, copy,
		    pairs, 7, 3);
	bench_ratio("  hash + accumulate alone on 2 cores:     ", ceiling,
		    copy, pairs, 7, 3);
	printf("sweep: %zu frames, %.0f MB (%s)\n", r.n_frames, mb,
	       rc == 0 ? "ok" : "FAILED");
	for (k = 1; k >= 0; k--) {
		double m[BENCH_MAX_PAIRS], mc[BENCH_MAX_PAIRS];
		char label[128];

		rates(mb, wall[k], m, pairs);
		rates(mb, cpu[k], mc, pairs);
		for (i = 0; i < pairs; i++)
			v[i] = m[i];
		snprintf(label, sizeof(label), "stray reduce, full frames "
			 "(%s): %.0f MB/s =", what[k],
			 bench_median(v, pairs, &lo, &hi));
		bench_ratio(label, m, copy, pairs, 6, 3);
		/* on a shared machine the wall clock counts others too */
		bench_ratio("  per CPU second, x memcpy:", mc, copy, pairs,
			    6, 3);
	}
	printf("workspace: %.1f bytes per pixel\n",
	       (double)r.workspace_bytes / ((double)ROWS * COLS));
	stray_reduce_sweep_result_free(&r);
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd) != 0 || rc != 0;
}
