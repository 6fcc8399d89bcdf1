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
	double percent;		/* done / total, 0-100 */
	int angle_no, n_angles;	/* the current angle, 1-based, of n */
	char step[80];		/* the frame to take next, in words */
};

struct rig_sweep {
	struct rig_lab *lab;
	const struct rig_sweep_cfg *cfg;
	struct stray_sweep_manifest mf;	/* the folder, written through the
					 * sweep store (libstray/sweep) */
	double *angles;		/* in the order taken; may return to one */
	int *visit_no;		/* per angle: earlier visits to it */
	int n_angles, i_angle;
	int at_angle;		/* stage verified at angles[i_angle] */
	int have[STRAY_SWEEP_FRAMETYP_COUNT];	/* exposure found at this angle */
	int expo_it;		/* test frames of the search in progress */
	double t_exp_s[STRAY_SWEEP_FRAMETYP_COUNT];
	int slot[STRAY_SWEEP_FRAMETYP_COUNT];
	struct rig_image img;
	long done_at_open, taken;
	double t_open_s;
	double busy_s;		/* HAL time spent in steps (not paused) */
	long steps;		/* steps taken, test frames included */
	double utc_floor;	/* the last frame's time: none goes before */
	char owner[48];		/* who started (or resumed) it */
	int finished;
};

/* The sweep's angle list from cfg (start..stop by step, inclusive). */
int rig_sweep_angles(const struct rig_sweep_cfg *cfg, double **angles,
		     int *n, struct rig_error *err);

/* Flags of rig_sweep_open and rig_sweep_claim. */
#define RIG_SWEEP_RESUME 1	/* continue the sweep already in dir */
#define RIG_SWEEP_FORCE_PLAN 2	/* resume even if the plan changed */

/*
 * Open a sweep folder: rig_sweep_claim then rig_sweep_attach.  Claim
 * takes the folder (the sweep store's one-writer lock, refused with
 * RIG_EIO while another writer holds it) and checks the plan
 * (plan.json, rig_sweep_plan_check) without touching the lab; attach
 * binds the lab and readies the first step.
 */
int rig_sweep_open(struct rig_sweep *sw, struct rig_lab *lab,
		   const char *dir, int flags, struct rig_error *err);
int rig_sweep_claim(struct rig_sweep *sw, const struct rig_config *cfg,
		    const char *dir, int flags, struct rig_error *err);
int rig_sweep_attach(struct rig_sweep *sw, struct rig_lab *lab,
		     struct rig_error *err);
/* The same for an owner (a user name, kept in plan.json and status). */
int rig_sweep_open_as(struct rig_sweep *sw, struct rig_lab *lab,
		      const char *dir, int flags, const char *owner,
		      struct rig_error *err);
int rig_sweep_claim_as(struct rig_sweep *sw, const struct rig_config *cfg,
		       const char *dir, int flags, const char *owner,
		       struct rig_error *err);

/*
 * The plan (plan.c): the config values that shape the folder (angles,
 * repeats, exposure limits and target, camera window and saturation, ND
 * transmissions) kept in dir/plan.json.  Written when absent; if stored
 * and different, refused with RIG_EINVAL naming the first key that
 * differs, unless force, when the new plan replaces it.
 */
int rig_sweep_plan_check(const char *dir, const struct rig_config *cfg,
			 int force, struct rig_error *err);
/* The same, recording owner (and the time) in plan.json when the plan is
 * first written; "owner" and "created_utc" are notes, never compared. */
int rig_sweep_plan_check_as(const char *dir, const struct rig_config *cfg,
			    int force, const char *owner,
			    struct rig_error *err);
/* Free space (space.c): the bytes of one frame on disk (FITS blocks and
 * its manifest row), and RIG_EIO when dir's file system (its parent's,
 * before it exists) has less than frames of them with 10 % and 16 MB to
 * spare, naming both figures. */
double rig_sweep_bytes_per_frame(const struct rig_config *cfg);
int rig_sweep_space_check(const char *dir, const struct rig_config *cfg,
			  long frames, struct rig_error *err);

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
/* One test frame of that search (at most RIG_EXPO_ITER_MAX make a
 * search); *done = 1 when (t, slot) is settled.  The sweep takes one per
 * step, so the daemon serves its clients between test frames. */
#define RIG_EXPO_ITER_MAX 24
int rig_expo_step(struct rig_lab *lab, struct rig_image *img,
		  double *t_exp_s, int *slot, int *done, struct rig_error *err);

/* The read-back keywords of a frame (readback.c): ANGLERB, the stage's
 * read-back, and on an INDI lab FILTER/FILTERRB (slot commanded and read
 * back, the device's numbering), EXPTIMRB (the camera's own EXPTIME) and
 * LAMP/LAMPRB (lamp commanded and read back, 1 on); returns how many. */
#define RIG_SWEEP_RB_KEYS 6
size_t rig_sweep_readback_keys(const struct rig_lab *lab,
			       struct stray_sweep_key k[RIG_SWEEP_RB_KEYS]);

/* Peak of the 3-pixel row-neighbourhood mean of an image, DN. */
double rig_image_peak3(const struct rig_image *img);

#endif /* RIG_SWEEP_H */
