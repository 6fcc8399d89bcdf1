/*
 * frames_job.h - a run of `stray frames` as one call: frames rendered for
 * a source at theta (or a given alpha), both star detectors, the false
 * and lost stars counted against the FDR model and its extension, the
 * first frames kept as a sweep folder and a PNG when asked.  `stray
 * frames` (tools/cmd_frames.c) parses into struct frames_opts, calls
 * frames_run and prints the job; Python calls the same.
 */
#ifndef STRAY_FRAMES_FRAMES_JOB_H
#define STRAY_FRAMES_FRAMES_JOB_H

#include <stdint.h>

#include "frames/frames_lost.h"
#include "frames/frames_run.h"
#include "stray/error.h"
#include "stray/fdr_setup.h"
#include "stray/file.h"
#include "stray/sweep_store.h"

/* What a run renders and keeps (the options of `stray frames`). */
struct frames_opts {
	const char *curve;	/* system curve: alpha = curve(theta_deg) */
	const char *map;	/* focal map (stray trace --focal-map), NULL */
	const char *out_dir;	/* the first `save` frames as a sweep folder */
	const char *png;	/* the first frame in false colour */
	double theta_deg, alpha, frames, window, seed, save, mag_max;
	int has_theta, has_alpha;
	double att[4];		/* q_ib (normalised); has_att = 0: random field */
	int has_att;
	const char *catalogue, *truth;	/* real catalogue, truth-star CSV */
	double epoch;		/* the catalogue's epoch, Julian year */
	/* Each rendered frame (cols x rows DN) as it is made, for a caller
	 * that keeps them (the Python package); NULL: none. */
	int (*on_frame)(void *user, const uint16_t *dn, int cols, int rows,
			size_t index, size_t total, struct stray_error *err);
	void *on_frame_user;
};

/* One frame, one star; the false-star positions kept per detector. */
#define FRAMES_MAX_DET 200000
#define FRAMES_MAX_STARS 200000
#define FRAMES_MAX_FALSE_POS 200000

/* One detector's result over the run. */
struct frames_det_result {
	const char *name;	/* "thesis" or "threshold" */
	double measured, sigma, extended, found;	/* per frame */
	double dispersion;	/* frame-to-frame variance / mean */
	double extended_no_map_term;	/* extended without the map's term */
	char verdict[512];	/* frames_diagnose's reading */
};

/* The run: its options, its buffers and its results. */
struct frames_job {
	const struct fdr_setup *s;	/* loaded (fdr_setup_load) */
	struct frames_opts a;
	int cols, rows, col0, row0;
	double k_px, alpha, wmean, stars_sum;
	double clip_frac;		/* pixels whose background clips */
	double resid_rel;		/* the map's background-error term */
	double flat[2];			/* extended rates without it */
	float *weight, *expect, *tiles;
	uint16_t *dn;
	struct stray_star *stars;
	struct frames_detection *det;
	struct frames_detect_out out[2];
	struct frames_detect_cfg dc;
	struct frames_model fm;
	struct frames_rates rates;
	struct frames_alpha_req req;
	struct stray_region_map map;
	struct frames_evidence ev[2];
	struct frames_lost lost;	/* stars found per magnitude (issue 28) */
	long n_false[2], n_found[2];
	double n_false_sq[2];		/* sum of per-frame counts squared */
	struct frames_det_result res[2];	/* thesis, threshold */
	uint16_t *det_rows;		/* detector row of each frame row */
	struct stray_dir_out dir;	/* out_dir, filled as a temporary */
	struct stray_sweep_manifest mf;
	int dir_open, store_open;
};

/* The defaults: 1 frame, seed 1, 3 saved, stars to m = 10, epoch 2000. */
void frames_opts_init(struct frames_opts *o);

/*
 * Render, detect and count o->frames frames for the loaded setup s (job
 * zeroed by the caller; s must outlive the job).  An error names the
 * file, option or field; out_dir is then not left behind.
 */
int frames_run(struct frames_job *job, const struct fdr_setup *s,
	       const struct frames_opts *o, struct stray_error *err);

/* The job's buffers (the job itself is the caller's). */
void frames_job_free(struct frames_job *job);

#endif /* STRAY_FRAMES_FRAMES_JOB_H */
