/*
 * farm_set.h - private to the farm: the traces in flight and the one
 * queue of their pieces (no MPI here; farm_master.c moves the messages).
 *
 * A sweep's designs are farmed together: every design is a trace whose
 * pieces (piece.h) join one queue, its main pass waiting only for its own
 * pilot and guide.  A rank is given pieces of the traces whose scene it
 * already built, oldest trace first; only when none of those has a piece
 * free does it open the next trace, and once all are open it joins the
 * trace in flight with the most pieces free.  So a rank builds about (designs / ranks) scenes plus
 * one or two at the end, a trace is opened only when a rank has nothing
 * else to do (few are open at once), and the last traces are finished
 * by all ranks together.  Every piece lands in its own rows and each trace's
 * statistics sum batches in batch order: the bits of tracer_trace(), in
 * whatever order the pieces come back (tracer/batches.h).
 */
#ifndef STRAY_MPI_FARM_SET_H
#define STRAY_MPI_FARM_SET_H

#include <pthread.h>

#include "farm_proto.h"

#define FARM_PREFETCH 2	/* pieces queued per rank: no idle gap between two */

enum farm_phase {
	FT_CLOSED,	/* not opened yet */
	FT_PILOT,	/* pilot pieces out; the main pass waits for the guide */
	FT_MAIN,	/* guide built (or none wanted): main pieces out */
	FT_DONE,	/* every piece in: for the caller */
	FT_OVER		/* handed to the caller and freed */
};

/* What a rank holds of a trace (farm_set.held). */
enum { HELD_JOB = 1, HELD_GUIDE = 2 };

struct farm_pass {
	struct tracer_trace_opts o;	/* the pass's options, all angles */
	struct piece *plan;
	size_t n_plan, next, done;
	struct tracer_result r;
	double *s2;			/* pilot: [batch][cell][theta] */
	double *light;			/* pilot of light_paths: B's
					 * [batch][theta][TRACER_LIGHT_STATS] */
	struct tracer_path_table *tables;	/* per batch (record_paths) */
};

struct farm_trace {
	struct tracer_scene_spec spec;	/* the caller's strings */
	const struct tracer_trace_opts *o;
	int phase;			/* enum farm_phase */
	struct farm_pass pass[2];	/* PIECE_PILOT, PIECE_MAIN */
	struct tracer_guide *g;		/* NULL until built (or unguided) */
	double *ratio;			/* light_paths: B's samples per path
					 * per angle, with the guide; or NULL */
	/* rank 0's own thread: the caller's scene, or one it built */
	const struct tracer_scene *scene;
	struct tracer_scene own;
	int own_built;
	double t0, seconds;
};

/* Called for each finished trace on rank 0's MPI thread; it may take
 * the result (then leave *res zeroed). */
typedef int (*farm_done_fn)(void *user, size_t i, struct tracer_result *res,
			    struct stray_error *err);

struct farm_set {
	struct farm_trace *t;
	size_t n, n_open, first_live;	/* traces [0, first_live) are over */
	int size;			/* ranks */
	unsigned char *held;		/* [rank * n + trace]: HELD_* */
	int chunks[2];			/* angle chunks per pass */
	pthread_mutex_t lock;		/* all of the above, and failed */
	pthread_cond_t wake;		/* rank 0's thread: new pieces */
	int failed, quit;
	struct stray_error err;
	farm_done_fn done;
	void *user;
};

/* A piece taken for a rank, and the messages that must precede it. */
struct farm_take {
	size_t trace;
	int pass;
	size_t k;		/* index into the pass's plan */
	int send_job, send_guide;
};

/*
 * n traces; scene: rank 0's scene of a single trace (NULL: rank 0's
 * thread builds the scenes of the traces it works on).  The angle chunks
 * give the ranks about 2 pieces each in each pass over all traces.
 */
int farm_set_init(struct farm_set *fs, const struct tracer_trace_item *items,
		  size_t n, const struct tracer_scene *scene, int size,
		  farm_done_fn done, void *user, struct stray_error *err);
void farm_set_free(struct farm_set *fs);

/* Under fs->lock: the next piece for rank (1: taken, 0: none now). */
int farm_set_take(struct farm_set *fs, int rank, struct farm_take *t);

/* Under fs->lock: a piece's payload into its trace (a pilot's last
 * piece builds the guide); nonzero on failure (fs->err set). */
int farm_set_apply(struct farm_set *fs, const struct farm_take *t,
		   const double *payload);

/* The piece t stands for. */
const struct piece *farm_set_piece(const struct farm_set *fs,
				   const struct farm_take *t);

/* 1 when every trace is over, or the set failed. */
int farm_set_finished(struct farm_set *fs);

/* Rank 0's MPI thread: hand each finished trace to the caller (fs->done)
 * and free it; drop(ctx, rank, trace) for every other rank that built its
 * scene.  Nonzero when the caller failed (fs->err set). */
int farm_set_collect(struct farm_set *fs,
		     void (*drop)(void *ctx, int rank, size_t trace),
		     void *ctx);

/* Rank 0's own worker thread (pthread start routine; arg: farm_set). */
void *farm_set_local(void *arg);

#endif /* STRAY_MPI_FARM_SET_H */
