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

void *stray_rs_ws_take(struct workspace *w, size_t bytes, size_t at);
void stray_rs_ws_give(struct workspace *w, size_t bytes);
int stray_rs_load_frame(struct workspace *w, const struct stray_sweep_entry *e,
			struct stray_frame *f, uint16_t *pix,
			struct stray_error *err);
int stray_rs_at_frame(struct workspace *w, const struct stray_sweep_entry *e,
		      int rc, struct stray_error *err);
int stray_rs_setup(struct workspace *w, struct stray_error *err);
void stray_rs_start_reading(struct workspace *w,
			    const struct stray_reduce_sweep_result *res);
int stray_rs_dark_levels(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err);
int stray_rs_dark_pixels(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err);
int stray_rs_plan_visits(struct workspace *w,
			 struct stray_reduce_sweep_result *res,
			 struct stray_error *err);
int stray_rs_check_visits(struct workspace *w,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err);
int stray_rs_light_buffers(struct workspace *w,
			   struct stray_reduce_sweep_result *res,
			   struct stray_error *err);
int stray_rs_all_timed(const struct workspace *w, double *span);
int stray_rs_reduce_visit(struct workspace *w, size_t v,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err);
int stray_rs_track_ghosts(struct workspace *w,
			  struct stray_reduce_sweep_result *res,
			  struct stray_error *err);
int stray_rs_add_common(struct workspace *w,
			struct stray_reduce_sweep_result *res, int *redo,
			struct stray_error *err);
int stray_rs_to_commanded(struct workspace *w,
			  struct stray_reduce_sweep_result *res);

#endif /* STRAY_REDUCE_SWEEP_WS_H */
