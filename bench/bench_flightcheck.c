/*
 * bench_flightcheck.c - the per-frame step of `stray flightcheck` on full
 * 2592 x 1944 frames (issue 18 target: >= 10 frames/s on 2 cores):
 * background, plate solution on the catalogue, star calibration.  Frames
 * are rendered in memory first (not timed); the step runs on 2 OpenMP
 * threads.  Printed as frames per second and as a ratio against one
 * memcpy of the frame in the same run.
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flightcheck.h"
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
	double q[NF][4], base, t0, t, t_tt = 835300000.0;
	int i, matched = 0;

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
	t0 = now_s();
	for (i = 0; i < 20; i++) {
		memcpy(cp, dn + (i % NF) * n, n * 2);
		cp[i] ^= 1;
	}
	base = (now_s() - t0) / 20;
	t0 = now_s();
#pragma omp parallel num_threads(2) reduction(+:matched)
	{
		struct fc_work w;
		struct fc_frame o;
		int k;

		if (fc_work_alloc(&w, &cfg) == 0) {
#pragma omp for schedule(dynamic)
			for (k = 0; k < REPS; k++) {
				fc_frame_analyse(&cfg, &w, dn + (k % NF) * n,
						 q[k % NF], t_tt, &o);
				matched += o.n_match;
			}
			fc_work_free(&w);
		}
	}
	t = (now_s() - t0) / REPS;
	printf("flightcheck per-frame step, full frame, 2 threads: %.1f frames/s (%.4f s/frame = %.0f memcpy; target >= 10 frames/s), %.0f stars matched per frame\n",
	       1.0 / t, t, t / base, (double)matched / REPS);
	printf("(baseline: memcpy of the 10 MB frame = %.2f ms, this run)\n",
	       base * 1e3);
	free(e);
	free(dn);
	free(cp);
	return 0;
}
