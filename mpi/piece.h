/*
 * piece.h - one task of a distributed trace: some batches of a pass at a
 * contiguous subset of the angles (tracer/batches.h says why such a
 * piece computes exactly the numbers of the whole trace), packed as a
 * flat array of doubles (the MPI message), and put back into the
 * assembled result.  No MPI here: the unit tests run it in one process.
 */
#ifndef STRAY_MPI_PIECE_H
#define STRAY_MPI_PIECE_H

#include <stddef.h>

#include "tracer/batches.h"

enum piece_pass { PIECE_PILOT = 0, PIECE_MAIN = 1 };

struct piece {
	int pass;		/* enum piece_pass */
	int batch;
	int theta_first, theta_n;	/* angles [first, first + n) */
	int light;		/* pilot with opts.light_paths: B's statistics
				 * too (set from the pass's options, not sent) */
};

/* Doubles in a piece's payload (the pilot's: at most, its s2 tallies
 * encoded; path records not counted). */
size_t piece_payload_len(const struct piece *p);

/* Payload: batch_paths, casts, connections, energy[TRACER_ENERGY_N],
 * power[theta_n][TRACER_ORDERS], then (p->light) B's pilot statistics
 * [theta_n][TRACER_LIGHT_STATS], then (pilot) s2[cells][theta_n] as runs
 * of nonzero values (n_runs, then start, length, values per run) or,
 * when not shorter, -1 and all the values (piece.c). */
#define PIECE_HEAD (3 + TRACER_ENERGY_N)

/*
 * Trace piece p of the pass whose options are po (all angles; the pilot's
 * options for PIECE_PILOT) with guide g (NULL for the pilot) into out
 * (piece_payload_len doubles).
 */
int piece_run(const struct tracer_scene *s,
	      const struct tracer_trace_opts *po,
	      const struct tracer_guide *g, const struct piece *p,
	      double *out, struct stray_error *err);

/*
 * As piece_run, into a payload it (re)allocates: *len doubles.  With
 * po->record_paths the fixed part is followed by the batch's path
 * records of these angles: their count, then per record theta_index
 * (of the whole sweep), seq's high and low 32 bits, value, n_paths.
 */
#define PIECE_PATH_FIELDS 5
int piece_run_alloc(const struct tracer_scene *s,
		    const struct tracer_trace_opts *po,
		    const struct tracer_guide *g, const struct piece *p,
		    double **out, size_t *len, struct stray_error *err);

/* Payload length checks: 1 when len doubles can be piece p's payload of
 * a pass with (record_paths) or without path records (with payload: its
 * encoding read through, too). */
int piece_payload_ok(const struct piece *p, int record_paths,
		     const double *payload, size_t len);

/*
 * The path records of a payload into tables[p->batch] (one table per
 * batch; a batch's chunks hold different angles).  Once every piece is
 * in, tracer_paths_merge the tables into the result in batch order:
 * the sums of tracer_trace(), though not its table's slot order.
 */
int piece_apply_paths(const struct piece *p, const double *payload,
		      struct tracer_path_table *tables);

/* An empty result of pass po (all angles, all batches) to assemble into;
 * s2 (pilot, may be NULL) gets [batches][cells][n_theta] zeros. */
int piece_result_alloc(const struct tracer_trace_opts *po,
		       struct tracer_result *r, double **s2);

/* Put a piece's payload into its rows of r (and s2; and, p->light,
 * light [batches][n_theta][TRACER_LIGHT_STATS]: tracer_light_alloc's). */
void piece_apply(const struct piece *p, const double *payload,
		 struct tracer_result *r, double *s2, double *light);

/* The pieces of a pass in the order handed out: per batch, angle chunks
 * from the last (high angles: most connections) down; n_chunks >= 1;
 * light 0 (the caller sets it for a pilot of opts.light_paths). */
size_t piece_plan(int pass, int n_batches, size_t n_theta, int n_chunks,
		  struct piece *out);

#endif /* STRAY_MPI_PIECE_H */
