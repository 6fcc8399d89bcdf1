/*
 * sweep.h - the measurement sweep of thesis §3.2 (method.md §4): per
 * angle, FULL frames (beam on the aperture), AMBIENT frames (beam blocked)
 * and DARK frames (shutter shut) at each exposure used, `repeats` of each;
 * exposure and ND chosen so the brightest region sits just below
 * saturation (0.01-1 s, ND slots stepped when exposure alone cannot).
 *
 * The manifest is the only state: each step works out the next frame from
 * what manifest.csv already holds, so resuming after a crash or kill -9 is
 * opening the folder with resume = 1 and stepping on.
 */
#ifndef RIG_SWEEP_H
#define RIG_SWEEP_H

#include <stdio.h>

#include "rig/lab.h"
#include "stray/sweep_store.h"

struct rig_progress {
	long done, total;	/* frames (total estimated until known) */
	double elapsed_s, eta_s;	/* HAL clock */
	double theta_deg;
	int finished;
};

struct rig_sweep {
	struct rig_lab *lab;
	const struct rig_sweep_cfg *cfg;
	struct stray_sweep_manifest mf;	/* the folder, written through the
					 * sweep store (libstray/sweep) */
	double *angles;
	int n_angles, i_angle;
	int at_angle;		/* stage verified at angles[i_angle] */
	int have[STRAY_SWEEP_FRAMETYP_COUNT];	/* exposure found at this angle */
	double t_exp_s[STRAY_SWEEP_FRAMETYP_COUNT];
	int slot[STRAY_SWEEP_FRAMETYP_COUNT];
	struct rig_image img;
	long done_at_open, taken;
	double t_open_s;
	int finished;
};

/* The sweep's angle list from cfg (start..stop by step, inclusive). */
int rig_sweep_angles(const struct rig_sweep_cfg *cfg, double **angles,
		     int *n, struct rig_error *err);

int rig_sweep_open(struct rig_sweep *sw, struct rig_lab *lab,
		   const char *dir, int resume, struct rig_error *err);
/* Take the next frame (or finish); on failure the lab is made safe. */
int rig_sweep_step(struct rig_sweep *sw, struct rig_error *err);
void rig_sweep_progress(const struct rig_sweep *sw, struct rig_progress *p);
/* Step to the end, printing a progress line per frame to out (or NULL). */
int rig_sweep_run(struct rig_sweep *sw, FILE *out, struct rig_error *err);
void rig_sweep_close(struct rig_sweep *sw);

/*
 * Exposure search: from (t, slot), capture test frames until the peak of
 * the 3-pixel row-neighbourhood mean (thesis §3.2, isolated hot or
 * saturated pixels suppressed) lies in [0.5, 0.95] of saturation, or the
 * exposure is at t_max with the clearest slot.
 */
int rig_expo_search(struct rig_lab *lab, struct rig_image *img,
		    double *t_exp_s, int *slot, struct rig_error *err);

/* Peak of the 3-pixel row-neighbourhood mean of an image, DN. */
double rig_image_peak3(const struct rig_image *img);

#endif /* RIG_SWEEP_H */
