/*
 * stray_reduce_sweep.h - a sweep folder to the lens curve (thesis §3.2), driving
 * the libstray/reduce math from the frames on disk.
 *
 * Streaming: the manifest (metadata only) is read whole; the frames are
 * read one at a time, darks twice (levels, then hot/dead pixels), then
 * each visit of the gimbal to an angle (consecutive manifest rows at one
 * angle) through two per-pixel accumulators.  Memory is a fixed number of
 * per-pixel buffers - about 31 bytes a pixel, the size of 16 frames -
 * plus a few numbers per visit, whatever the number of frames.
 */
#ifndef STRAY_REDUCE_SWEEP_H
#define STRAY_REDUCE_SWEEP_H

#include <stddef.h>

#include "stray/error.h"
#include "stray/reduce_curve.h"
#include "stray/reduce_dark.h"
#include "stray/reduce_frame.h"
#include "stray/reduce_ghost.h"
#include "stray/reduce_response.h"

#define STRAY_REDUCE_TRACKS_MAX 16
#define STRAY_REDUCE_PIXLIST_MAX 1000

struct stray_reduce_sweep_opts {
	struct stray_bayer_map map;
	struct stray_response_opts response;
	struct stray_ghost_opts ghost;
	double hot_sigma;
	int verify_sha256;
	int keep_image;		/* keep J at image_theta_deg */
	double image_theta_deg;
	int no_common;		/* leave frame-common noise out of var(P)
				 * (reduce_common.h); it is still measured */
	int no_angle_rb;	/* keep visits at their read-back angles
				 * (ANGLERB ignored, reduce_angle.h) */
	int visits_only;	/* stop at the visits (a folder with no
				 * on-axis visit, merged by
				 * stray_reduce_sweeps): no curve, no
				 * frame-common noise, no ANGLERB carry,
				 * no ghost tracks */
};

void stray_reduce_sweep_opts_default(struct stray_reduce_sweep_opts *o);

struct stray_reduce_sweep_pixel {
	long row, col;		/* detector coordinates */
	int flag;		/* enum stray_pixel_flag */
};

struct stray_reduce_sweep_result {
	size_t n_rows, n_cols, n_frames, n_darks;
	long col0;		/* detector column of stored column 0 */
	size_t n_points;
	struct stray_curve_point *points;
	struct stray_drift drift;
	int has_monitor;	/* frames carried MONITOR */
	/* Visits in acquisition order, with their row-collapsed profiles. */
	size_t n_visits;
	struct stray_visit *visits;
	double *profiles;	/* n_visits * n_cols */
	/* Pixels. */
	struct stray_mask_stats mask;
	size_t n_pixlist;
	struct stray_reduce_sweep_pixel pixlist[STRAY_REDUCE_PIXLIST_MAX];
	unsigned long n_sat_samples;	/* saturated samples left out */
	size_t n_sat_pixels;		/* pixel-visits saturated throughout */
	/* Ghost tracks (ascending theta), points owned by the result. */
	size_t n_tracks;
	struct stray_ghost_track tracks[STRAY_REDUCE_TRACKS_MAX];
	double p0;		/* P(0) the curve is normalised by */
	/* J at the requested angle (fig. 3.8), n_rows * n_cols, or NULL. */
	float *image;
	double image_theta_deg;
	size_t workspace_bytes;	/* per-pixel buffers, for the bound */
	/* Frame-common relative noise per frame (reduce_common.h), added to
	 * every var(P), and the degrees of freedom it was measured on. */
	double common_rel_sigma;
	size_t common_dof;
	/* Largest |commanded - read-back| angle (ANGLERB) a visit was
	 * carried over (reduce_angle.h), deg. */
	double angle_rb_max_deg;
	/* 1: the drift was fitted against time (every manifest row had its
	 * date_obs), 0: against row order (a folder without times). */
	int drift_in_time;
	double span_s;		/* first to last frame, s (drift_in_time) */
	double t0_utc;		/* the first frame's date_obs (drift_in_time) */
	size_t n_folders;	/* folders merged (stray_reduce_sweeps) */
};

/* Reduce DIR; res is zeroed first and must be freed. */
int stray_reduce_sweep(const char *dir,
		       const struct stray_reduce_sweep_opts *o,
		       struct stray_reduce_sweep_result *res,
		       struct stray_error *err);

/*
 * Several sweep folders of one lens reduced together (merge.c): each
 * folder's frames with its own darks and masks, their visits put on one
 * time line (every manifest needs date_obs) and one curve fitted, P(0)
 * and its drift from the on-axis visits of all of them (at least one
 * folder must have one).  Same window (rows, columns) in all; ghost
 * tracks, pixel lists and the J image are the first on-axis folder's.
 */
int stray_reduce_sweeps(const char *const *dirs, size_t n_dirs,
			const struct stray_reduce_sweep_opts *o,
			struct stray_reduce_sweep_result *res,
			struct stray_error *err);

void stray_reduce_sweep_result_free(struct stray_reduce_sweep_result *res);

#endif /* STRAY_REDUCE_SWEEP_H */
