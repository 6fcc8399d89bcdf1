/*
 * bench_flightcheck.c - the per-frame step of `stray flightcheck` on full
 * 2592 x 1944 frames (issue 18 target: >= 10 frames/s on 2 cores):
 * background, plate solution on the catalogue, star calibration.  Frames
 * are rendered in memory first (not timed); the step runs on 2 OpenMP
 * threads.  Printed as frames per second and as a ratio against one
 * memcpy of the frame timed right before, in alternating rounds (memcpy,
 * step, memcpy, ...; BENCH_PAIRS, bench_alt.h): median and min-max.
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_alt.h"
#include "mission/flightcheck.h"
#include "stray/aem.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

#define COLS 2592
#define ROWS 1944
#define NF 4		/* distinct frames */
#define REPS 40		/* frames analysed */

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int main(void)
{
	static struct stray_cat_star cat[200000];
	static struct stray_star st[100000];
	const struct stray_sensor *sn = stray_sensor_st16_like();
	struct stray_fluxes fl;
	struct stray_frame_cfg c;
	struct fc_cfg cfg;
	size_t n = (size_t)COLS * ROWS, nc, ns;
	float *e = malloc(n * sizeof(float));
	uint16_t *dn = malloc(NF * n * sizeof(uint16_t)), *cp = malloc(n * 2);
	double q[NF][4], base[BENCH_MAX_PAIRS], t[BENCH_MAX_PAIRS], t0, lo, hi;
	double fps[BENCH_MAX_PAIRS], t_tt = 835300000.0;
	char label[256];
	int i, p, matched = 0, pairs = bench_pairs();

	if (!e || !dn || !cp || stray_reference_fluxes(sn, &fl, NULL))
		return 1;
	fc_cfg_init(&cfg, sn, &fl, COLS, ROWS, 0, 0);
	stray_frame_cfg_defaults(&c, COLS, ROWS);
	c.stray_e = 600.0;
	c.dark_e = 0.4;
	c.read_noise_e = 3.0;
	for (i = 0; i < NF; i++) {
		struct stray_camera cam;
		double a = 0.7 * i, m[3][3] = {
			{ cos(a), sin(a), 0.0 }, { 0.0, 0.0, 1.0 },
			{ sin(a), -cos(a), 0.0 } };	/* boresight on the equator */

		stray_dcm_q(m, q[i]);
		stray_q_dcm(q[i], cam.m_ih);
		cam.f_px = cfg.f_px;
		cam.cx = cfg.cx;
		cam.cy = cfg.cy;
		stray_catalogue_cone(STRAY_CATALOGUE_SEED, cam.m_ih[2], 14.0, 10.0,
				     cat, 200000, &nc);
		ns = stray_camera_stars(&cam, cat, nc, COLS, ROWS, 8.0, cfg.f0_e,
					st, 100000);
		stray_frame_expect(&c, st, ns, e);
		stray_frame_sample(&c, e, (uint64_t)i + 7, dn + i * n);
	}
	for (p = 0; p < pairs; p++) {
		t0 = now_s();
		for (i = 0; i < 20; i++) {
			memcpy(cp, dn + (i % NF) * n, n * 2);
			cp[i] ^= 1;
		}
		base[p] = (now_s() - t0) / 20;
		matched = 0;
		t0 = now_s();
#pragma omp parallel num_threads(2) reduction(+:matched)
		{
			struct fc_work w;
			struct fc_frame o;
			int k;

			if (fc_work_alloc(&w, &cfg) == 0) {
#pragma omp for schedule(dynamic)
				for (k = 0; k < REPS; k++) {
					fc_frame_analyse(&cfg, &w,
						dn + (k % NF) * n, q[k % NF],
						t_tt, &o);
					matched += o.n_match;
				}
				fc_work_free(&w);
			}
		}
		t[p] = (now_s() - t0) / REPS;
		fps[p] = 1.0 / t[p];
	}
	snprintf(label, sizeof(label), "flightcheck per-frame step, full "
		 "frame, 2 threads: %.1f frames/s (target >= 10 frames/s), "
		 "%.0f stars matched per frame;\n  median (min-max) of %d "
		 "alternating pairs, s/frame in memcpy:",
		 bench_median(fps, pairs, &lo, &hi),
		 (double)matched / REPS, pairs);
	bench_ratio(label, t, base, pairs, 6, 1);
	printf("(baseline: memcpy of the 10 MB frame = %.2f ms, this run, "
	       "median)\n", 1e3 * bench_median(base, pairs, &lo, &hi));
	free(e);
	free(dn);
	free(cp);
	return 0;
}
