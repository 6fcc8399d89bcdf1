/*
 * farm_master.c - rank 0 of the task farm: cut a trace into pieces, hand
 * them out to free ranks (and to a thread of its own), put the results in
 * their rows, and notice a rank that stops answering (farm.h).
 */
#include <mpi.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "farm_proto.h"

struct farm_config farm_config = { 0, 300.0, 0 };
struct farm_stats farm_last;

#define PREFETCH 2	/* pieces queued per rank: no idle gap between two */

static int broken;
static char remote_error[256];

/* One pass being worked through, shared with rank 0's own thread. */
struct pass_run {
	const struct tracer_scene *s;
	const struct tracer_trace_opts *po;
	const struct tracer_guide *g;
	struct piece *plan;
	size_t n_plan, next, done;
	struct tracer_result *r;
	double *s2;
	struct tracer_path_table *tables;	/* per batch (record_paths) */
	pthread_mutex_t lock;
	int failed;
	struct stray_error err;
};

/* Per remote rank: the pieces it holds, oldest first. */
struct rank_state {
	size_t queue[PREFETCH];
	int n;
	double last_heard;
};

int farm_broken(void)
{
	return broken;
}

/* The next piece, or -1 when all are handed out. */
static long take(struct pass_run *p)
{
	long k;

	pthread_mutex_lock(&p->lock);
	k = !p->failed && p->next < p->n_plan ? (long)p->next++ : -1;
	pthread_mutex_unlock(&p->lock);
	return k;
}

/* A piece's payload into the result (under p->lock). */
static int apply(struct pass_run *p, const struct piece *pc,
		 const double *payload, struct stray_error *err)
{
	piece_apply(pc, payload, p->r, p->s2);
	if (p->tables && piece_apply_paths(pc, payload, p->tables))
		return stray_error_set(err, STRAY_ENOMEM, "paths",
				       "out of memory recording paths");
	p->done++;
	return STRAY_OK;
}

static void *local_worker(void *arg)
{
	struct pass_run *p = arg;
	double *buf = NULL;
	long k;

	while ((k = take(p)) >= 0) {
		const struct piece *pc = &p->plan[k];
		struct stray_error e;
		size_t len;
		int rc;

		stray_error_clear(&e);
		rc = piece_run_alloc(p->s, p->po, p->g, pc, &buf, &len, &e);
		pthread_mutex_lock(&p->lock);
		if (!rc)
			rc = apply(p, pc, buf, &e);
		if (rc) {
			p->failed = 1;
			p->err = e;
		}
		pthread_mutex_unlock(&p->lock);
	}
	free(buf);
	return NULL;
}

/*
 * A send that cannot hang: a stopped rank never takes a message too big
 * to be sent eagerly, so wait for it no longer than the task timeout.
 */
static int send_timed(const void *buf, int count, MPI_Datatype type,
		      int rank, int tag, struct stray_error *err)
{
	double t0 = farm_now();
	MPI_Request req;
	int done = 0;

	MPI_Isend(buf, count, type, rank, tag, MPI_COMM_WORLD, &req);
	for (;;) {
		MPI_Test(&req, &done, MPI_STATUS_IGNORE);
		if (done)
			return STRAY_OK;
		if (farm_now() - t0 > farm_config.task_timeout_s)
			break;
		farm_nap();
	}
	broken = 1;	/* the request stays pending: the job is aborted */
	snprintf(remote_error, sizeof(remote_error), "rank %d took no message "
		 "for %.0f s (killed or stalled; --task-timeout)", rank,
		 farm_now() - t0);
	return stray_error_set(err, STRAY_EIO, "mpi", remote_error);
}

static int send_piece(struct pass_run *p, struct rank_state *rs, int rank,
		      size_t k)
{
	int msg[4] = { p->plan[k].pass, p->plan[k].batch,
		       p->plan[k].theta_first, p->plan[k].theta_n };

	if (rs->n == 0)
		rs->last_heard = farm_now();
	rs->queue[rs->n++] = k;
	*(p->plan[k].pass == PIECE_PILOT ? &farm_last.pilot_bytes :
	  &farm_last.task_bytes) += sizeof(msg);
	return send_timed(msg, 4, MPI_INT, rank, TAG_TASK, &p->err);
}

/* Receive one message from a rank; returns nonzero on a fatal one. */
static int receive(struct pass_run *p, struct rank_state *ranks,
		   MPI_Status *st, double **buf, size_t *cap)
{
	struct rank_state *rs = &ranks[st->MPI_SOURCE];
	const struct piece *pc;
	int count, rc;

	if (st->MPI_TAG == TAG_ERROR) {
		char line[200] = "";

		MPI_Recv(line, sizeof(line) - 1, MPI_CHAR, st->MPI_SOURCE,
			 TAG_ERROR, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
		snprintf(remote_error, sizeof(remote_error), "rank %d: %s",
			 st->MPI_SOURCE, line);
		return stray_error_set(&p->err, STRAY_EIO, "mpi",
				       remote_error);
	}
	MPI_Get_count(st, MPI_DOUBLE, &count);
	if (rs->n == 0 || st->MPI_TAG != TAG_RESULT)
		return stray_error_set_value(&p->err, STRAY_EIO, "mpi",
			"unexpected message from rank", st->MPI_SOURCE);
	pc = &p->plan[rs->queue[0]];
	if (!piece_payload_ok(pc, p->tables != NULL, NULL, (size_t)count))
		return stray_error_set_value(&p->err, STRAY_EIO, "mpi",
			"result of the wrong size from rank", st->MPI_SOURCE);
	if ((size_t)count > *cap) {
		double *nb = realloc(*buf, (size_t)count * sizeof(double));

		if (!nb)
			return stray_error_set(&p->err, STRAY_ENOMEM, "mpi",
					       "out of memory");
		*buf = nb;
		*cap = (size_t)count;
	}
	MPI_Recv(*buf, count, MPI_DOUBLE, st->MPI_SOURCE, TAG_RESULT,
		 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
	if (!piece_payload_ok(pc, p->tables != NULL, *buf, (size_t)count))
		return stray_error_set_value(&p->err, STRAY_EIO, "mpi",
			"malformed result from rank", st->MPI_SOURCE);
	*(pc->pass == PIECE_PILOT ? &farm_last.pilot_bytes :
	  &farm_last.task_bytes) += (uint64_t)count * sizeof(double);
	(*(pc->pass == PIECE_PILOT ? &farm_last.remote_pilot :
	   &farm_last.remote_tasks))++;
	pthread_mutex_lock(&p->lock);
	rc = apply(p, pc, *buf, &p->err);
	pthread_mutex_unlock(&p->lock);
	if (rc)
		return rc;
	memmove(rs->queue, rs->queue + 1, (size_t)(rs->n - 1) * sizeof(size_t));
	rs->n--;
	rs->last_heard = farm_now();
	return STRAY_OK;
}

/* A busy rank silent for longer than the timeout is lost. */
static int check_silence(struct pass_run *p, const struct rank_state *ranks,
			 int size)
{
	double now = farm_now();
	int r;

	for (r = 1; r < size; r++)
		if (ranks[r].n > 0 &&
		    now - ranks[r].last_heard > farm_config.task_timeout_s) {
			snprintf(remote_error, sizeof(remote_error),
				 "rank %d sent no result for %.0f s "
				 "(killed or stalled; --task-timeout)", r,
				 now - ranks[r].last_heard);
			return stray_error_set(&p->err, STRAY_EIO, "mpi",
					       remote_error);
		}
	return STRAY_OK;
}

/* Rank 0's loop: keep every rank fed, collect, watch the clock. */
static int serve_pass(struct pass_run *p, struct rank_state *ranks, int size)
{
	double *buf = NULL;
	size_t cap = 0;
	int r, rc = STRAY_OK, done;

	for (;;) {
		int flag = 0;
		MPI_Status st;
		long k;

		for (r = 1; r < size && !rc; r++)
			while (!rc && ranks[r].n < PREFETCH &&
			       (k = take(p)) >= 0)
				rc = send_piece(p, &ranks[r], r, (size_t)k);
		if (rc)
			break;
		MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag,
			   &st);
		rc = flag ? receive(p, ranks, &st, &buf, &cap) :
		     check_silence(p, ranks, size);
		pthread_mutex_lock(&p->lock);
		done = p->done == p->n_plan || p->failed;
		pthread_mutex_unlock(&p->lock);
		if (rc || done)
			break;
		if (!flag)
			farm_nap();
	}
	free(buf);
	return rc;
}

/* Angle chunks: one (paths serve every angle) unless the batches alone
 * cannot give each rank a few pieces. */
static int chunks_for(const struct tracer_trace_opts *po, int size)
{
	int c = farm_config.angle_chunks;

	if (c <= 0)
		c = (4 * size + po->n_batches - 1) / po->n_batches;
	if ((size_t)c > po->n_theta)
		c = (int)po->n_theta;
	return c < 1 ? 1 : c;
}

/* The batches' path records into the result in batch order, as
 * tracer_trace() merges them: the same sums, bit for bit. */
static int merge_tables(struct pass_run *p, struct tracer_result *r,
			struct stray_error *err)
{
	int b;

	for (b = 0; b < p->po->n_batches; b++)
		if (tracer_paths_merge(&r->paths, &p->tables[b])) {
			tracer_result_free(r);
			return stray_error_set(err, STRAY_ENOMEM, "paths",
				"out of memory recording paths");
		}
	return STRAY_OK;
}

static void free_tables(struct pass_run *p)
{
	int b;

	if (!p->tables)
		return;
	for (b = 0; b < p->po->n_batches; b++)
		tracer_paths_free(&p->tables[b]);
	free(p->tables);
}

static int run_pass(const struct tracer_scene *s,
		    const struct tracer_trace_opts *po,
		    const struct tracer_guide *g, int pass,
		    struct tracer_result *r, double **s2,
		    struct stray_error *err)
{
	struct pass_run p;
	struct rank_state *ranks;
	pthread_t tid;
	int size, chunks, rc;

	MPI_Comm_size(MPI_COMM_WORLD, &size);
	chunks = chunks_for(po, size);
	memset(&p, 0, sizeof(p));
	p.s = s;
	p.po = po;
	p.g = g;
	p.r = r;
	p.plan = malloc((size_t)po->n_batches * (size_t)chunks *
			sizeof(*p.plan));
	ranks = calloc((size_t)size, sizeof(*ranks));
	if (!p.plan || !ranks ||
	    piece_result_alloc(po, r, pass == PIECE_PILOT ? s2 : NULL)) {
		free(p.plan);
		free(ranks);
		return stray_error_set(err, STRAY_ENOMEM, "mpi",
				       "out of memory");
	}
	p.s2 = pass == PIECE_PILOT ? *s2 : NULL;
	if (po->record_paths &&
	    !(p.tables = calloc((size_t)po->n_batches, sizeof(*p.tables)))) {
		free(p.plan);
		free(ranks);
		tracer_result_free(r);
		return stray_error_set(err, STRAY_ENOMEM, "mpi",
				       "out of memory");
	}
	p.n_plan = piece_plan(pass, po->n_batches, po->n_theta, chunks, p.plan);
	*(pass == PIECE_PILOT ? &farm_last.pilot_tasks : &farm_last.tasks) +=
		p.n_plan;
	pthread_mutex_init(&p.lock, NULL);
	stray_error_clear(&p.err);
	rc = pthread_create(&tid, NULL, local_worker, &p);
	if (rc == 0) {
		rc = serve_pass(&p, ranks, size);
		if (rc) {	/* stop the local thread too */
			pthread_mutex_lock(&p.lock);
			p.failed = 1;
			pthread_mutex_unlock(&p.lock);
		}
		pthread_join(tid, NULL);
	}
	if (rc || p.failed) {
		broken = 1;	/* ranks may still hold pieces: abort the job */
		*err = p.err;
		rc = err->code ? err->code : STRAY_EIO;
		tracer_result_free(r);
	}
	if (p.tables && !rc)
		rc = merge_tables(&p, r, err);
	free_tables(&p);
	pthread_mutex_destroy(&p.lock);
	free(p.plan);
	free(ranks);
	return rc;
}

static int send_all(const void *buf, int len, int tag,
		    struct stray_error *err)
{
	int size, r, rc = STRAY_OK;

	MPI_Comm_size(MPI_COMM_WORLD, &size);
	for (r = 1; r < size && !rc; r++) {
		rc = send_timed(buf, len, MPI_BYTE, r, tag, err);
		farm_last.job_bytes += (uint64_t)len;
	}
	return rc;
}

/* The pilot's pieces, then the guide to every rank. */
static int make_guide(const struct tracer_scene *s,
		      const struct tracer_trace_opts *o, struct tracer_guide *g,
		      struct stray_error *err)
{
	struct tracer_trace_opts po;
	struct tracer_result pr;
	double *s2 = NULL;
	int rc;

	tracer_pilot_opts(o, &po);
	rc = run_pass(s, &po, NULL, PIECE_PILOT, &pr, &s2, err);
	if (rc)
		return rc;
	rc = tracer_guide_from_pilot(g, &pr, s2);
	tracer_result_free(&pr);
	free(s2);
	if (rc)
		return stray_error_set(err, STRAY_ENOMEM, "guide",
				       "out of memory");
	return send_all(g, (int)sizeof(*g), TAG_GUIDE, err);
}

int farm_trace(const struct tracer_scene_spec *spec,
	       const struct tracer_scene *s,
	       const struct tracer_trace_opts *o, struct tracer_result *res,
	       struct stray_error *err)
{
	struct tracer_guide *g = NULL;
	double t0 = farm_now();
	size_t len;
	char *job;
	int rc, size;

	MPI_Comm_size(MPI_COMM_WORLD, &size);
	memset(&farm_last, 0, sizeof(farm_last));
	if ((o->record_paths && !farm_config.paths_any_order) ||
	    o->dump_paths || o->map_n || o->focal) {
		if (size == 1)	/* one rank: the whole trace, threads and all */
			return tracer_trace(s, o, res, err);
		return stray_error_set(err, STRAY_EINVAL, "mpi",
			"--paths-out, --top, --dump-paths, --map and "
			"--focal-map need one rank (run without mpirun)");
	}
	rc = tracer_trace_check(s, o, err);	/* before any rank is bothered */
	if (rc)
		return rc;
	job = farm_job_pack(spec, o, &len);
	if (!job)
		return stray_error_set(err, STRAY_ENOMEM, "mpi", "out of memory");
	rc = send_all(job, (int)len, TAG_JOB, err);
	free(job);
	if (!rc && tracer_pilot_wanted(o)) {
		g = malloc(sizeof(*g));
		rc = g ? make_guide(s, o, g, err) :
		     stray_error_set(err, STRAY_ENOMEM, "guide", "out of memory");
	}
	if (!rc)
		rc = run_pass(s, o, g, PIECE_MAIN, res, NULL, err);
	if (!broken && send_all(NULL, 0, TAG_ENDJOB, err) && !rc)
		rc = err->code;
	if (!rc)
		res->seconds = farm_now() - t0;
	free(g);
	return rc;
}

void farm_quit(void)
{
	struct stray_error err;

	stray_error_clear(&err);
	send_all(NULL, 0, TAG_QUIT, &err);
}
