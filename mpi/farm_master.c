/*
 * farm_master.c - rank 0 of the task farm: hand the pieces of the traces
 * in flight (farm_set.h) to free ranks while a thread of its own works
 * through the same queue, put the results in their rows, give each
 * finished trace to the caller while the ranks go on, and notice a rank
 * that stops answering (farm.h).
 */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "farm_set.h"
#include "tracer/scene_load.h"

static int broken;
static char remote_error[256];

/* Per remote rank: the pieces it holds, oldest first. */
struct rank_state {
	struct farm_take queue[FARM_PREFETCH];
	int n;
	double last_heard;
};

int farm_broken(void)
{
	return broken;
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

/*
 * Rank 0's sends during a set do not wait: a rank may itself be sending
 * a large result to rank 0 (a rendezvous) while rank 0 sends it a guide
 * or a job; each send's buffer is kept until MPI says it went.
 */
struct outbox {
	MPI_Request *req;
	void **buf;
	double *t0;
	int *rank;
	size_t n, cap;
};

static int post(struct outbox *ob, void *buf, int count, MPI_Datatype type,
		int rank, int tag, struct stray_error *err)
{
	if (ob->n == ob->cap) {
		size_t cap = 2 * ob->cap + 16;
		MPI_Request *r = realloc(ob->req, cap * sizeof(*r));
		void **b = r ? realloc(ob->buf, cap * sizeof(*b)) : NULL;
		double *t = b ? realloc(ob->t0, cap * sizeof(*t)) : NULL;
		int *k = t ? realloc(ob->rank, cap * sizeof(*k)) : NULL;

		if (r)
			ob->req = r;
		if (b)
			ob->buf = b;
		if (t)
			ob->t0 = t;
		if (!k) {
			free(buf);
			return stray_error_set(err, STRAY_ENOMEM, "mpi",
					       "out of memory");
		}
		ob->rank = k;
		ob->cap = cap;
	}
	MPI_Isend(buf, count, type, rank, tag, MPI_COMM_WORLD,
		  &ob->req[ob->n]);
	ob->buf[ob->n] = buf;
	ob->t0[ob->n] = farm_now();
	ob->rank[ob->n++] = rank;
	return STRAY_OK;
}

/* Free what went; a send pending longer than the timeout: a lost rank. */
static int flush(struct outbox *ob, struct stray_error *err)
{
	double now = farm_now();
	size_t i = 0;

	while (i < ob->n) {
		int done = 0;

		MPI_Test(&ob->req[i], &done, MPI_STATUS_IGNORE);
		if (!done) {
			if (now - ob->t0[i] > farm_config.task_timeout_s) {
				broken = 1;	/* pending: the job is aborted */
				snprintf(remote_error, sizeof(remote_error),
					 "rank %d took no message for %.0f s "
					 "(killed or stalled; --task-timeout)",
					 ob->rank[i], now - ob->t0[i]);
				return stray_error_set(err, STRAY_EIO, "mpi",
						       remote_error);
			}
			i++;
			continue;
		}
		free(ob->buf[i]);
		ob->n--;
		ob->req[i] = ob->req[ob->n];
		ob->buf[i] = ob->buf[ob->n];
		ob->t0[i] = ob->t0[ob->n];
		ob->rank[i] = ob->rank[ob->n];
	}
	return STRAY_OK;
}

/* Wait until every send went (or a rank is lost), then free the box. */
static int drain(struct outbox *ob, struct stray_error *err)
{
	int rc = STRAY_OK;

	while (!rc && ob->n) {
		rc = flush(ob, err);
		if (!rc && ob->n)
			farm_nap();
	}
	if (!rc) {
		free(ob->req);
		free(ob->buf);
		free(ob->t0);
		free(ob->rank);
	}
	return rc;
}

/* The job (and guide) a rank needs before the piece, then the piece. */
static int send_piece(struct farm_set *fs, struct outbox *ob,
		      struct rank_state *rs, int rank,
		      const struct farm_take *tk, struct stray_error *err)
{
	const struct farm_trace *t = &fs->t[tk->trace];
	const struct piece *pc = farm_set_piece(fs, tk);
	int *msg = malloc(5 * sizeof(int)), rc = STRAY_OK;

	if (!msg)
		return stray_error_set(err, STRAY_ENOMEM, "mpi",
				       "out of memory");
	msg[0] = (int)tk->trace;
	msg[1] = pc->pass;
	msg[2] = pc->batch;
	msg[3] = pc->theta_first;
	msg[4] = pc->theta_n;
	if (tk->send_job) {
		size_t len;
		char *job = farm_job_pack(&t->spec, t->o, (int)tk->trace, &len);

		rc = job ? post(ob, job, (int)len, MPI_BYTE, rank, TAG_JOB,
				err) :
		     stray_error_set(err, STRAY_ENOMEM, "mpi", "out of memory");
		farm_last.job_bytes += len;
		farm_last.scene_builds++;
	}
	if (!rc && tk->send_guide) {	/* B's ratios packed after it */
		size_t nr = t->ratio ? t->o->n_theta : 0;
		size_t len = sizeof(struct farm_guide_msg) + nr * sizeof(double);
		struct farm_guide_msg *gm = malloc(len);

		if (gm) {
			gm->trace = (int64_t)tk->trace;
			gm->g = *t->g;
			if (nr)
				memcpy(gm + 1, t->ratio, nr * sizeof(double));
		}
		rc = gm ? post(ob, gm, (int)len, MPI_BYTE, rank, TAG_GUIDE,
			       err) :
		     stray_error_set(err, STRAY_ENOMEM, "mpi", "out of memory");
		farm_last.job_bytes += len;
	}
	if (rc) {
		free(msg);
		return rc;
	}
	if (rs->n == 0)
		rs->last_heard = farm_now();
	rs->queue[rs->n++] = *tk;
	*(pc->pass == PIECE_PILOT ? &farm_last.pilot_bytes :
	  &farm_last.task_bytes) += 5 * sizeof(int);
	return post(ob, msg, 5, MPI_INT, rank, TAG_TASK, err);
}

/* Receive one message from a rank; returns nonzero on a fatal one. */
static int receive(struct farm_set *fs, struct rank_state *ranks,
		   MPI_Status *st, double **buf, size_t *cap,
		   struct stray_error *err)
{
	struct rank_state *rs = &ranks[st->MPI_SOURCE];
	const struct piece *pc;
	int count, rc, record;

	if (st->MPI_TAG == TAG_ERROR) {
		char line[200] = "";

		MPI_Recv(line, sizeof(line) - 1, MPI_CHAR, st->MPI_SOURCE,
			 TAG_ERROR, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
		snprintf(remote_error, sizeof(remote_error), "rank %d: %s",
			 st->MPI_SOURCE, line);
		return stray_error_set(err, STRAY_EIO, "mpi", remote_error);
	}
	MPI_Get_count(st, MPI_DOUBLE, &count);
	if (rs->n == 0 || st->MPI_TAG != TAG_RESULT)
		return stray_error_set_value(err, STRAY_EIO, "mpi",
			"unexpected message from rank", st->MPI_SOURCE);
	pc = farm_set_piece(fs, &rs->queue[0]);
	record = fs->t[rs->queue[0].trace].pass[pc->pass].o.record_paths;
	if (!piece_payload_ok(pc, record, NULL, (size_t)count))
		return stray_error_set_value(err, STRAY_EIO, "mpi",
			"result of the wrong size from rank", st->MPI_SOURCE);
	if ((size_t)count > *cap) {
		double *nb = realloc(*buf, (size_t)count * sizeof(double));

		if (!nb)
			return stray_error_set(err, STRAY_ENOMEM, "mpi",
					       "out of memory");
		*buf = nb;
		*cap = (size_t)count;
	}
	MPI_Recv(*buf, count, MPI_DOUBLE, st->MPI_SOURCE, TAG_RESULT,
		 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
	if (!piece_payload_ok(pc, record, *buf, (size_t)count))
		return stray_error_set_value(err, STRAY_EIO, "mpi",
			"malformed result from rank", st->MPI_SOURCE);
	*(pc->pass == PIECE_PILOT ? &farm_last.pilot_bytes :
	  &farm_last.task_bytes) += (uint64_t)count * sizeof(double);
	(*(pc->pass == PIECE_PILOT ? &farm_last.remote_pilot :
	   &farm_last.remote_tasks))++;
	pthread_mutex_lock(&fs->lock);
	rc = farm_set_apply(fs, &rs->queue[0], *buf);
	pthread_mutex_unlock(&fs->lock);
	if (rc)
		return rc;
	memmove(rs->queue, rs->queue + 1,
		(size_t)(rs->n - 1) * sizeof(rs->queue[0]));
	rs->n--;
	rs->last_heard = farm_now();
	return STRAY_OK;
}

/* A busy rank silent for longer than the timeout is lost. */
static int check_silence(const struct rank_state *ranks, int size,
			 struct stray_error *err)
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
			return stray_error_set(err, STRAY_EIO, "mpi",
					       remote_error);
		}
	return STRAY_OK;
}

/* Keep every rank fed (FARM_PREFETCH pieces each). */
static int feed(struct farm_set *fs, struct outbox *ob,
		struct rank_state *ranks, struct stray_error *err)
{
	int r, rc = STRAY_OK;

	for (r = 1; r < fs->size && !rc; r++)
		while (!rc && ranks[r].n < FARM_PREFETCH) {
			struct farm_take tk;
			int got;

			pthread_mutex_lock(&fs->lock);
			got = farm_set_take(fs, r, &tk);
			pthread_mutex_unlock(&fs->lock);
			if (!got)
				break;
			rc = send_piece(fs, ob, &ranks[r], r, &tk, err);
		}
	return rc;
}

/* farm_set_collect's drop: a rank lets go of a finished trace's scene. */
struct drop_ctx {
	int rc;
	struct outbox *ob;
	struct stray_error *err;
};

static void drop_scene(void *ctx, int rank, size_t trace)
{
	struct drop_ctx *d = ctx;
	int *id = malloc(sizeof(*id));

	if (d->rc)
		free(id);
	else if (!id)
		d->rc = stray_error_set(d->err, STRAY_ENOMEM, "mpi",
					"out of memory");
	else {
		*id = (int)trace;
		d->rc = post(d->ob, id, 1, MPI_INT, rank, TAG_ENDJOB, d->err);
	}
}

/* Pieces the other ranks hold. */
static int held(const struct rank_state *ranks, int size)
{
	int r, n = 0;

	for (r = 1; r < size; r++)
		n += ranks[r].n;
	return n;
}

/* Rank 0's loop: feed, collect, hand finished traces on, watch the clock. */
static int serve(struct farm_set *fs, struct rank_state *ranks,
		 struct stray_error *err)
{
	struct outbox ob;
	struct drop_ctx drop = { STRAY_OK, &ob, err };
	double *buf = NULL;
	size_t cap = 0;
	int rc = STRAY_OK, finished, failed;

	memset(&ob, 0, sizeof(ob));
	for (;;) {
		int flag = 0;
		MPI_Status st;

		rc = feed(fs, &ob, ranks, err);
		if (!rc)
			rc = flush(&ob, err);
		if (rc)
			break;
		MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag,
			   &st);
		rc = flag ? receive(fs, ranks, &st, &buf, &cap, err) :
		     check_silence(ranks, fs->size, err);
		if (!rc)	/* the caller's refusal fails the set (fs->err) */
			farm_set_collect(fs, drop_scene, &drop);
		if (!rc)
			rc = drop.rc;
		pthread_mutex_lock(&fs->lock);
		finished = farm_set_finished(fs);
		failed = fs->failed;
		pthread_mutex_unlock(&fs->lock);
		if (rc || (finished && (!failed || !held(ranks, fs->size))))
			break;	/* a failed set: the ranks finish what they hold
				 * first, and the job ends with one line */
		if (!flag)
			farm_nap();
	}
	free(buf);
	if (!rc)	/* the last ENDJOBs: their buffers are ours */
		rc = drain(&ob, err);
	return rc;
}

/* The set on all ranks: rank 0's thread and the loop above. */
static int run_set(struct farm_set *fs, struct stray_error *err)
{
	struct rank_state *ranks = calloc((size_t)fs->size, sizeof(*ranks));
	pthread_t tid;
	int rc;

	if (!ranks)
		return stray_error_set(err, STRAY_ENOMEM, "mpi",
				       "out of memory");
	rc = pthread_create(&tid, NULL, farm_set_local, fs);
	if (rc) {
		free(ranks);
		return stray_error_set(err, STRAY_EIO, "mpi",
				       "cannot start a thread");
	}
	rc = serve(fs, ranks, err);
	pthread_mutex_lock(&fs->lock);
	if (rc || fs->failed) {	/* stop the local thread too */
		if (!fs->failed) {
			fs->err = *err;
			fs->failed = 1;
		}
		pthread_cond_broadcast(&fs->wake);
	}
	pthread_mutex_unlock(&fs->lock);
	pthread_join(tid, NULL);
	if (rc)		/* ranks may still hold pieces: abort the job */
		broken = 1;
	if (fs->failed) {	/* else (a bad design): every piece came back */
		*err = fs->err;
		rc = err->code ? err->code : STRAY_EIO;
	}
	free(ranks);
	return rc;
}

/* farm_trace's callback: the trace's result is the caller's. */
static int take_result(void *user, size_t i, struct tracer_result *res,
		       struct stray_error *err)
{
	struct tracer_result *out = user;

	(void)i;
	(void)err;
	*out = *res;
	memset(res, 0, sizeof(*res));
	return STRAY_OK;
}

int farm_trace(const struct tracer_scene_spec *spec,
	       const struct tracer_scene *s,
	       const struct tracer_trace_opts *o, struct tracer_result *res,
	       struct stray_error *err)
{
	struct tracer_trace_item item;
	struct farm_set fs;
	double t0 = farm_now();
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
	if (size > 1 && o->light_ratio &&
	    !(o->light_paths && tracer_pilot_wanted(o)))
		return stray_error_set(err, STRAY_EINVAL, "mpi", "a caller's "
			"light_ratio is not carried (light_paths sizes B)");
	item.spec = *spec;
	item.o = o;
	memset(res, 0, sizeof(*res));
	rc = farm_set_init(&fs, &item, 1, s, size, take_result, res, err);
	if (rc)
		return rc;
	rc = run_set(&fs, err);
	farm_set_free(&fs);
	if (rc)
		tracer_result_free(res);
	else
		res->seconds = farm_now() - t0;
	return rc;
}

/* A set's callback through the runner's (const result) one. */
struct set_user {
	tracer_item_done_fn done;
	void *user;
};

static int hand_on(void *user, size_t i, struct tracer_result *res,
		   struct stray_error *err)
{
	const struct set_user *u = user;

	return u->done(u->user, i, res, err);
}

int farm_trace_set(const struct tracer_trace_item *items, size_t n,
		   tracer_item_done_fn done, void *user,
		   struct stray_error *err)
{
	struct set_user u = { done, user };
	struct farm_set fs;
	size_t i;
	int rc = STRAY_OK, size;

	MPI_Comm_size(MPI_COMM_WORLD, &size);
	memset(&farm_last, 0, sizeof(farm_last));
	/* each trace's scene is checked as it opens (farm_set.c) */
	for (i = 0; !rc && i < n; i++)
		if (items[i].o->record_paths || items[i].o->dump_paths ||
		    items[i].o->map_n || items[i].o->focal)
			rc = stray_error_set(err, STRAY_EINVAL, "mpi",
				"a set of traces records no paths, dumps or maps");
	if (rc || n == 0)
		return rc;
	rc = farm_set_init(&fs, items, n, NULL, size, hand_on, &u, err);
	if (rc)
		return rc;
	rc = run_set(&fs, err);
	farm_set_free(&fs);
	return rc;
}

void farm_quit(void)
{
	struct stray_error err;
	int size, r;

	MPI_Comm_size(MPI_COMM_WORLD, &size);
	stray_error_clear(&err);
	for (r = 1; r < size; r++)
		if (send_timed(NULL, 0, MPI_BYTE, r, TAG_QUIT, &err))
			return;
}
