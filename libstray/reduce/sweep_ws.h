/*
 * sweep_ws.h - what the files of stray_reduce_sweep share (private to
 * libstray/reduce/): the workspace and the visit plan, frames read into
 * it (sweep_read.c), the darks (sweep_darks.c), the visits and the curve
 * (sweep_visits.c); sweep.c runs them in order.
 */
#ifndef STRAY_REDUCE_SWEEP_WS_H
#define STRAY_REDUCE_SWEEP_WS_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"
#include "stray/reduce_angle.h"
#include "stray/reduce_common.h"
#include "stray/reduce_sweep.h"
#include "stray/sweep_store.h"
#include "prefetch.h"

/* Darks kept in memory between the two dark passes, at most. */
#define STRAY_REDUCE_DARK_CACHE 6

struct visit_plan {
	/* Manifest runs (darks skipped inside): the visit's own, and a run
	 * of the other type at the same angle when the sweep took all FULL
	 * frames in one pass and all AMBIENT frames in another. */
	size_t first[2], last[2], n_runs;
	size_t n_full, n_amb;
	size_t n_peaks;
	struct stray_ghost_peak peaks[STRAY_GHOST_PEAKS_MAX];
	/* Frame totals of its FULL [0] and AMBIENT [1] groups
	 * (reduce_common.h). */
	struct stray_common_group cg[2];
	double rb_sum;		/* ANGLERB (else ANGLE) over its light frames */
	size_t n_rb;
};

struct workspace {
	const char *dir;
	const struct stray_reduce_sweep_opts *o;
	struct stray_sweep_manifest man;
	struct stray_sweep_fits fits;		/* the frame being read */
	struct stray_sweep_buf file;	/* its bytes, when hashed */
	struct stray_prefetch pf;	/* the next ones, read and hashed */
	struct stray_sweep_header geo;	/* the first frame: the geometry */
	size_t n_pix;
	uint16_t *pix;
	struct stray_dark_model dark;
	uint8_t *mask;
	struct stray_accum full, amb;
	void *acc_mem[2];
	float *j, *var_j;
	double *prof_var, *ghost_scratch;
	struct visit_plan *plan;
	/* The phases' memory, and in it (beside the pixel statistics) the
	 * darks of pass 1 kept for pass 2. */
	unsigned char *arena;
	size_t arena_bytes, cache_at, cache_slots, n_cached;
	struct stray_frame cached[STRAY_REDUCE_DARK_CACHE];
	int monitor;		/* -1 unknown, else whether light frames
				 * carry MONITOR: all or none must */
	size_t bytes, peak_bytes;
};

/* Workspace memory (sweep_read.c): bytes of the arena at offset at,
 * counted in the phase's peak; given back at the phase's end. */
void *stray_rs_ws_take(struct workspace *w, size_t bytes, size_t at);
void stray_rs_ws_give(struct workspace *w, size_t bytes);
/* Frame e read (prefetched), checked against the geometry, decoded. */
int stray_rs_load_frame(struct workspace *w, const struct stray_sweep_entry *e,
			struct stray_frame *f, uint16_t *pix,
			struct stray_error *err);
/* rc of a step on frame e, the error located at its file. */
int stray_rs_at_frame(struct workspace *w, const struct stray_sweep_entry *e,
		      int rc, struct stray_error *err);
/* The first frame's geometry, the pixel buffers and the arena. */
int stray_rs_setup(struct workspace *w, struct stray_error *err);
/* The prefetch thread started on every frame in the order read. */
void stray_rs_start_reading(struct workspace *w,
			    const struct stray_reduce_sweep_result *res);
/*
 * The steps of the reduction, run in this order by sweep.c; each returns
 * STRAY_OK or an error naming the file and field:
 *   stray_rs_plan_visits    manifest runs paired into visits (sweep_visits.c)
 *   stray_rs_dark_levels    the darks' levels per read channel, pass 1
 *   stray_rs_dark_pixels    hot and dead pixels, pass 2 (sweep_darks.c)
 *   stray_rs_check_visits   a sweep with no FULL or AMBIENT frame refused
 *   stray_rs_light_buffers  the light accumulators, J and its variance
 *   stray_rs_track_ghosts   ghost tracks over the first visit of each angle
 */
typedef int stray_rs_step(struct workspace *w,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err);
stray_rs_step stray_rs_plan_visits, stray_rs_dark_levels,
	stray_rs_dark_pixels, stray_rs_check_visits, stray_rs_light_buffers,
	stray_rs_track_ghosts;
/* Whether every frame carries a time; the span in *span. */
int stray_rs_all_timed(const struct workspace *w, double *span);
/* Visit v accumulated to J (eq. 3.6) with its ghosts and profile. */
int stray_rs_reduce_visit(struct workspace *w, size_t v,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err);
/* Frame-common noise into the visits' sigma; *redo: refit. */
int stray_rs_add_common(struct workspace *w,
			struct stray_reduce_sweep_result *res, int *redo,
			struct stray_error *err);
/* The read-back angles to the commanded ones; 1: refit. */
int stray_rs_to_commanded(struct workspace *w,
			  struct stray_reduce_sweep_result *res);

#endif /* STRAY_REDUCE_SWEEP_WS_H */
