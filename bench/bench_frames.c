/*
 * bench_frames.c - rendering and star detection of a full 2592 x 1944
 * frame (issue 13 targets: render <= 0.3 s, detect <= 0.2 s on one core),
 * printed as seconds and as ratios against memcpy of the same frame timed
 * right before, in alternating runs (memcpy, render, detect, memcpy, ...;
 * bench_alt.h): median and min-max over the pairs, so the figures compare
 * across loaded and idle machines and show their noise.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_alt.h"
#include "frames/frames_detect.h"
#include "stray/frames.h"

#define COLS 2592
#define ROWS 1944

#define now_s bench_now

static double time_memcpy(uint16_t *a, uint16_t *b, size_t n)
{
	double t0 = now_s();
	int i;

	for (i = 0; i < 20; i++) {
		memcpy(b, a, n * sizeof(*a));
		a[i] ^= b[n - 1 - i];	/* keep the copy live */
	}
	return (now_s() - t0) / 20;
}

int main(void)
{
	static struct stray_star stars[20000];
	struct stray_frame_cfg c;
	struct stray_star_field f = { 196.0, -1.5, 10.0, 2.376e5 };
	struct frames_detect_cfg dc = { 100.0, 2.0, 128, 6.0, 1111.5, 51.2, 5 };
	struct frames_detection *det = malloc(2 * 200000 * sizeof(*det));
	struct frames_detect_out out[2] = { { det, 200000, 0 },
					    { det + 200000, 200000, 0 } };
	size_t n = (size_t)COLS * ROWS, ns;
	float *e = malloc(n * sizeof(float));
	uint16_t *dn = malloc(n * sizeof(uint16_t)), *cp = malloc(n * 2);
	double base[BENCH_MAX_PAIRS], t_r[BENCH_MAX_PAIRS], lo, hi;
	double t_d[3][BENCH_MAX_PAIRS], t0, v[BENCH_MAX_PAIRS];
	static const int which[3] = { FRAMES_DET_THESIS, FRAMES_DET_THRESHOLD,
				      FRAMES_DET_THESIS | FRAMES_DET_THRESHOLD };
	static const char *const name[3] = { "thesis window sum", "threshold",
					     "both" };
	char msg[128], label[160];
	int i, k, pairs = bench_pairs();

	if (!e || !dn || !cp || !det)
		return 1;
	stray_frame_cfg_defaults(&c, COLS, ROWS);
	c.stray_e = 800.0;	/* near 5 false stars per frame (thesis) */
	c.dark_e = 0.4;
	c.read_noise_e = 3.0;
	memset(dn, 1, n * 2);
	for (i = 0; i < pairs; i++) {
		base[i] = time_memcpy(dn, cp, n);
		t0 = now_s();
		stray_star_field_draw(&f, COLS, ROWS, (uint64_t)i, stars,
				      20000, &ns);
		stray_frame_expect(&c, stars, ns, e);
		stray_frame_sample(&c, e, (uint64_t)i + 99, dn);
		t_r[i] = now_s() - t0;
		for (k = 0; k < 3; k++) {
			t0 = now_s();
			if (frames_detect(dn, COLS, ROWS, &dc, which[k], out,
					  NULL, msg, sizeof(msg)))
				return 1;
			t_d[k][i] = now_s() - t0;
		}
	}
	printf("seconds and memcpy-times, median (min-max) of %d alternating "
	       "pairs:\n", pairs);
	for (i = 0; i < pairs; i++)
		v[i] = t_r[i];
	snprintf(label, sizeof(label), "render full frame (%zu stars, 800 "
		 "e-/px, noise): %.3f s (target <= 0.3 s) =", ns,
		 bench_median(v, pairs, &lo, &hi));
	bench_ratio(label, t_r, base, pairs, 6, 0);
	for (k = 0; k < 3; k++) {
		for (i = 0; i < pairs; i++)
			v[i] = t_d[k][i];
		snprintf(label, sizeof(label), "detect full frame (%-17s): "
			 "%.3f s (target <= 0.2 s) =", name[k],
			 bench_median(v, pairs, &lo, &hi));
		bench_ratio(label, t_d[k], base, pairs, 6, 0);
	}
	for (i = 0; i < pairs; i++)
		v[i] = base[i];
	printf("(baseline: memcpy of the 10 MB frame = %.2f ms, this run, "
	       "median)\n", 1e3 * bench_median(v, pairs, &lo, &hi));
	free(e);
	free(dn);
	free(cp);
	free(det);
	return 0;
}
