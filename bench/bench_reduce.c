/*
 * bench_reduce.c - full-frame (2592 x 1944) reduction throughput beside
 * this machine's memcpy bandwidth measured in the same run: the whole
 * `stray reduce` pipeline (SHA-256, cfitsio, both dark passes, two
 * groups, eq. 3.4-3.14, ghosts) over the sweep's bytes, and the
 * accumulation step alone (eq. 3.4-3.6).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stray/reduce_response.h"
#include "synth_sweep.h"
#include "stray/reduce_sweep.h"

#define ROWS 1944
#define COLS 2592
#define RUNS 3

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

int main(void)
{
	static struct synth_truth truth;
	struct synth_config c;
	struct stray_reduce_sweep_opts o;
	struct stray_reduce_sweep_result r;
	struct stray_error err;
	char dir[] = "/tmp/stray_bench_XXXXXX", cmd[64];
	double t0, t, mb, copy, acc, cpu, t_first = 0.0, cpu_first = 0.0;
	double t_best = 1e30, cpu_best = 1e30;
	clock_t c0;
	int rc = 0, k;

	if (!mkdtemp(dir))
		return 1;
	synth_default(&c);
	c.n_rows = ROWS;
	c.n_cols = COLS;
	c.n_angles = 1;		/* on axis: 2 darks, 2 FULL, 2 AMBIENT */
	c.revisit = 0;
	c.repeats = 2;
	c.darks_per_exp = 2;
	c.ghosts = 0;
	if (synth_write_sweep(dir, &c, &truth) != 0)
		return 1;
	copy = memcpy_mb_s((size_t)ROWS * COLS * 2);
	acc = accum_mb_s();
	stray_reduce_sweep_opts_default(&o);
	/* Best of RUNS, as the memcpy baseline is a best of 5; the first run
	 * is printed too: its fresh memory is the one a single `stray reduce`
	 * pays for (on a VM the host's page zeroing makes it vary most). */
	for (k = 0; k < RUNS; k++) {
		stray_error_clear(&err);
		if (k)
			stray_reduce_sweep_result_free(&r);
		t0 = now_s();
		c0 = clock();
		rc |= stray_reduce_sweep(dir, &o, &r, &err);
		t = now_s() - t0;
		cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
		if (k == 0)
			t_first = t, cpu_first = cpu;
		t_best = t < t_best ? t : t_best;
		cpu_best = cpu < cpu_best ? cpu : cpu_best;
	}
	/* the sweep's bytes, each frame counted once (its 16-bit pixels):
	 * the darks pass 2 needs come from memory, not read again */
	mb = (double)r.n_frames * ROWS * COLS * 2 / 1e6;
	printf("memcpy (baseline, this run):        %8.0f MB/s\n", copy);
	printf("accumulate one frame (eq. 3.4-3.6): %8.0f MB/s = %.3f x memcpy\n",
	       acc, acc / copy);
	printf("stray reduce, full frames (I/O, SHA-256, all passes): "
	       "%.0f MB/s = %.3f x memcpy (best of %d; %s)\n", mb / t_best,
	       mb / t_best / copy, RUNS, rc == 0 ? "ok" : "FAILED");
	/* on a shared machine the wall clock counts other processes too */
	printf("  per CPU second of the reduction: %.0f MB/s = %.3f x memcpy "
	       "(cpu %.2f s, wall %.2f s)\n", mb / cpu_best,
	       mb / cpu_best / copy, cpu_best, t_best);
	printf("  first run: %.0f MB/s = %.3f x memcpy (cpu %.2f s, wall "
	       "%.2f s)\n", mb / t_first, mb / t_first / copy, cpu_first,
	       t_first);
	printf("workspace: %.1f bytes per pixel\n",
	       (double)r.workspace_bytes / ((double)ROWS * COLS));
	stray_reduce_sweep_result_free(&r);
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd) != 0 || rc != 0;
}
