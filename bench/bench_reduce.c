/*
 * bench_reduce.c - full-frame (2592 x 1944) reduction throughput beside
 * this machine's memcpy bandwidth measured in the same run: the whole
 * `stray reduce` pipeline (SHA-256, cfitsio, both dark passes, two
 * groups, eq. 3.4-3.14, ghosts) over the sweep's bytes, with and
 * without the hash check, and its two largest per-frame steps alone:
 * the accumulation (eq. 3.4-3.6) and SHA-256.  Those two bound what two
 * cores can reach with the check on.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stray/reduce_response.h"
#include "stray/sweep_store.h"
#include "synth_sweep.h"
#include "stray/reduce_sweep.h"

#define ROWS 1944
#define COLS 2592
#define RUNS 3
#define ANGLES 4		/* 2 darks, then 3 FULL + 3 AMBIENT a visit */
#define REPEATS 3		/* frames averaged per group (thesis §3.2) */
#define STREAM_BYTES ((size_t)256 << 20)	/* 8x the L3 of this VM */

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

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

struct timing {
	double best, cpu, first, cpu_first;
	int rc;
};

/* Best of RUNS, as the memcpy baseline is a best of 5; the first run is
 * kept too: its fresh memory is the one a single `stray reduce` pays
 * for (on a VM the host's page zeroing makes it vary most). */
static void time_reduce(const char *dir, int verify, struct timing *t,
			struct stray_reduce_sweep_result *r)
{
	struct stray_reduce_sweep_opts o;
	struct stray_error err;
	int k;

	stray_reduce_sweep_opts_default(&o);
	o.verify_sha256 = verify;
	t->best = t->cpu = 1e30;
	t->rc = 0;
	for (k = 0; k < RUNS; k++) {
		double t0 = now_s(), wall, cpu;
		clock_t c0 = clock();

		stray_error_clear(&err);
		if (k)
			stray_reduce_sweep_result_free(r);
		t->rc |= stray_reduce_sweep(dir, &o, r, &err);
		wall = now_s() - t0;
		cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
		if (k == 0)
			t->first = wall, t->cpu_first = cpu;
		t->best = wall < t->best ? wall : t->best;
		t->cpu = cpu < t->cpu ? cpu : t->cpu;
	}
}

static void print_reduce(const char *what, const struct timing *t,
			 double mb, double copy)
{
	printf("stray reduce, full frames (%s): %.0f MB/s = %.3f x memcpy "
	       "(best of %d; %s)\n", what, mb / t->best, mb / t->best / copy,
	       RUNS, t->rc == 0 ? "ok" : "FAILED");
	/* on a shared machine the wall clock counts other processes too */
	printf("  per CPU second: %.0f MB/s = %.3f x memcpy (cpu %.2f s, "
	       "wall %.2f s); first run %.0f MB/s = %.3f x memcpy\n",
	       mb / t->cpu, mb / t->cpu / copy, t->cpu, t->best,
	       mb / t->first, mb / t->first / copy);
}

int main(void)
{
	static struct synth_truth truth;
	struct synth_config c;
	struct stray_reduce_sweep_result r;
	struct timing hashed, plain;
	char dir[] = "/tmp/stray_bench_XXXXXX", cmd[64];
	double mb, copy, stream, acc, sha, ceiling;

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
	copy = memcpy_mb_s((size_t)ROWS * COLS * 2);
	stream = memcpy_mb_s(STREAM_BYTES);
	acc = accum_mb_s();
	sha = sha256_mb_s();
	time_reduce(dir, 1, &hashed, &r);
	stray_reduce_sweep_result_free(&r);
	time_reduce(dir, 0, &plain, &r);
	/* the sweep's bytes, each frame counted once (its 16-bit pixels):
	 * the darks pass 2 needs come from memory, not read again */
	mb = (double)r.n_frames * ROWS * COLS * 2 / 1e6;
	/* every frame hashed and accumulated, nothing else, the two
	 * spread perfectly over 2 cores */
	ceiling = 2.0 / (1.0 / sha + 1.0 / acc);
	printf("memcpy of one frame (baseline, this run): %8.0f MB/s\n", copy);
	printf("memcpy of %zu MB (past the caches):      %8.0f MB/s = %.2f x "
	       "memcpy\n", STREAM_BYTES >> 20, stream, stream / copy);
	printf("accumulate one frame (eq. 3.4-3.6):       %8.0f MB/s = %.3f x "
	       "memcpy\n", acc, acc / copy);
	printf("SHA-256 of one frame (OpenSSL):           %8.0f MB/s = %.3f x "
	       "memcpy\n", sha, sha / copy);
	printf("  the hash alone on both cores:           %8.0f MB/s = %.3f x "
	       "memcpy (nothing else done)\n", 2.0 * sha, 2.0 * sha / copy);
	printf("  hash + accumulate alone on 2 cores:     %8.0f MB/s = %.3f x "
	       "memcpy (a ceiling with the check on)\n", ceiling,
	       ceiling / copy);
	printf("sweep: %zu frames, %.0f MB\n", r.n_frames, mb);
	print_reduce("I/O, SHA-256, all passes", &hashed, mb, copy);
	print_reduce("I/O, all passes, --no-verify", &plain, mb, copy);
	printf("workspace: %.1f bytes per pixel\n",
	       (double)r.workspace_bytes / ((double)ROWS * COLS));
	stray_reduce_sweep_result_free(&r);
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd) != 0 || hashed.rc != 0 || plain.rc != 0;
}
