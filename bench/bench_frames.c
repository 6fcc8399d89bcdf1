/*
 * bench_frames.c - rendering and star detection of a full 2592 x 1944
 * frame (issue 13 targets: render <= 0.3 s, detect <= 0.2 s on one core),
 * printed as seconds and as ratios against memcpy of the same frame in
 * the same run, so the figures compare across loaded and idle machines.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "frames_detect.h"
#include "stray/frames.h"

#define COLS 2592
#define ROWS 1944
#define REPS 5

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

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
	double base, t_r = 0, t_d[3] = { 0, 0, 0 }, t0;
	static const int which[3] = { FRAMES_DET_THESIS, FRAMES_DET_THRESHOLD,
				      FRAMES_DET_THESIS | FRAMES_DET_THRESHOLD };
	static const char *const name[3] = { "thesis window sum", "threshold",
					     "both" };
	char msg[128];
	int i, k;

	if (!e || !dn || !cp || !det)
		return 1;
	stray_frame_cfg_defaults(&c, COLS, ROWS);
	c.stray_e = 800.0;	/* near 5 false stars per frame (thesis) */
	c.dark_e = 0.4;
	c.read_noise_e = 3.0;
	memset(dn, 1, n * 2);
	base = time_memcpy(dn, cp, n);
	for (i = 0; i < REPS; i++) {
		t0 = now_s();
		stray_star_field_draw(&f, COLS, ROWS, (uint64_t)i, stars,
				      20000, &ns);
		stray_frame_expect(&c, stars, ns, e);
		stray_frame_sample(&c, e, (uint64_t)i + 99, dn);
		t_r += now_s() - t0;
		for (k = 0; k < 3; k++) {
			t0 = now_s();
			if (frames_detect(dn, COLS, ROWS, &dc, which[k], out,
					  NULL, msg, sizeof(msg)))
				return 1;
			t_d[k] += now_s() - t0;
		}
	}
	t_r /= REPS;
	printf("render full frame (%zu stars, 800 e-/px, noise): %.3f s = %6.0f memcpy (target <= 0.3 s)\n",
	       ns, t_r, t_r / base);
	for (k = 0; k < 3; k++)
		printf("detect full frame (%-17s):          %.3f s = %6.0f memcpy (target <= 0.2 s)\n",
		       name[k], t_d[k] / REPS, t_d[k] / REPS / base);
	printf("(baseline: memcpy of the 10 MB frame = %.2f ms, this run)\n",
	       base * 1e3);
	free(e);
	free(dn);
	free(cp);
	free(det);
	return 0;
}
