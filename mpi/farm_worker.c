/*
 * farm_worker.c - a rank other than 0: build the scene of each trace it
 * is given a piece of (a sweep has several in flight: farm_set.h), keep
 * it until rank 0 says the trace is over, trace the pieces it is handed,
 * send the payloads back.
 */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "farm_proto.h"
#include "stray/errfmt.h"
#include "tracer/scene_load.h"

/* One trace this rank holds the scene of. */
struct held_trace {
	char *job_buf;
	struct farm_job job;
	struct tracer_scene scene;
	struct tracer_lens lens;
	struct tracer_guide guide;
	double *ratio;		/* B's samples per path per angle, or NULL */
	int have_guide, failed;
};

struct worker {
	struct held_trace **t;
	size_t n, cap;
	double *payload;
};

static void send_error(const struct stray_error *err)
{
	char line[200];

	stray_error_format(err, line, sizeof(line));
	MPI_Send(line, (int)strlen(line) + 1, MPI_CHAR, 0, TAG_ERROR,
		 MPI_COMM_WORLD);
}

static struct held_trace *find(struct worker *w, int id)
{
	size_t i;

	for (i = 0; i < w->n; i++)
		if (w->t[i]->job.id == id)
			return w->t[i];
	return NULL;
}

static void drop(struct worker *w, int id)
{
	size_t i;

	for (i = 0; i < w->n; i++)
		if (w->t[i]->job.id == id) {
			struct held_trace *h = w->t[i];

			tracer_scene_free(&h->scene);
			tracer_lens_free(&h->lens);
			free(h->ratio);
			free(h->job_buf);
			free(h);
			w->t[i] = w->t[--w->n];
			return;
		}
}

/* Build the scene of a trace from its job; an error goes to rank 0. */
static void start_job(struct worker *w, int len)
{
	struct held_trace *h = calloc(1, sizeof(*h));
	char *buf = malloc(len > 0 ? (size_t)len : 1);
	struct stray_error err;
	int rc;

	MPI_Recv(buf, len, MPI_BYTE, 0, TAG_JOB, MPI_COMM_WORLD,
		 MPI_STATUS_IGNORE);
	stray_error_clear(&err);
	if (!h || (w->n == w->cap && !(w->t = realloc(w->t, (w->cap = 2 *
					w->cap + 4) * sizeof(*w->t))))) {
		free(h);
		free(buf);
		stray_error_set(&err, STRAY_ENOMEM, "mpi", "out of memory");
		send_error(&err);
		return;
	}
	h->job_buf = buf;
	tracer_scene_init(&h->scene);
	rc = farm_job_unpack(buf, (size_t)len, &h->job, &err);
	if (!rc) {
		drop(w, h->job.id);	/* a stale one of that number */
		rc = tracer_scene_load(h->job.scene, h->job.sets,
				       h->job.n_sets, &h->scene, &err);
	}
	if (!rc) {	/* the edits rank 0 made after loading */
		struct tracer_scene_spec ed = { h->job.scene, h->job.sets,
			h->job.n_sets, h->job.lens, h->job.beam_shift_z,
			h->job.abg_g };

		tracer_scene_spec_edit(&ed, &h->scene);
	}
	if (!rc && h->job.lens)
		rc = tracer_lens_load(h->job.lens, &h->lens, &err);
	if (!rc)
		rc = tracer_scene_commit(&h->scene, &err);
	h->job.o.lens = h->job.lens ? &h->lens : NULL;
	w->t[w->n++] = h;
	if (rc) {
		h->failed = 1;
		send_error(&err);
	}
}

/* The guide of a trace, and with light_paths its n_theta B ratios after
 * it (farm_proto.h); a malformed one goes to rank 0 as an error. */
static void take_guide(struct worker *w, int len)
{
	struct farm_guide_msg *gm = malloc(len > 0 ? (size_t)len : 1);
	struct held_trace *h;
	struct stray_error err;
	size_t nr;

	MPI_Recv(gm, gm ? len : 0, MPI_BYTE, 0, TAG_GUIDE, MPI_COMM_WORLD,
		 MPI_STATUS_IGNORE);
	if (!gm || (size_t)len < sizeof(*gm) || !(h = find(w, (int)gm->trace))) {
		free(gm);
		return;
	}
	nr = ((size_t)len - sizeof(*gm)) / sizeof(double);
	stray_error_clear(&err);
	if (nr * sizeof(double) != (size_t)len - sizeof(*gm) ||
	    (nr && nr != h->job.o.n_theta) ||
	    (!nr && h->job.o.light_paths))
		stray_error_set_value(&err, STRAY_EINVAL, "mpi",
			"guide message of the wrong size (bytes)", len);
	else if (nr && !(h->ratio = malloc(nr * sizeof(double))))
		stray_error_set(&err, STRAY_ENOMEM, "mpi", "out of memory");
	if (err.code) {
		if (!h->failed)
			send_error(&err);
		h->failed = 1;
		free(gm);
		return;
	}
	h->guide = gm->g;
	if (nr)
		memcpy(h->ratio, gm + 1, nr * sizeof(double));
	h->have_guide = 1;
	free(gm);
}

static void run_task(struct worker *w)
{
	struct tracer_trace_opts po;
	struct stray_error err;
	struct held_trace *h;
	struct piece p;
	int msg[5];
	size_t len = 0;

	MPI_Recv(msg, 5, MPI_INT, 0, TAG_TASK, MPI_COMM_WORLD,
		 MPI_STATUS_IGNORE);
	h = find(w, msg[0]);
	stray_error_clear(&err);
	if (!h) {
		stray_error_set_value(&err, STRAY_EINVAL, "mpi",
				      "piece of an unknown trace", msg[0]);
		send_error(&err);
		return;
	}
	if (h->failed)	/* the error is on its way; rank 0 will abort */
		return;
	p.pass = msg[1];
	p.batch = msg[2];
	p.theta_first = msg[3];
	p.theta_n = msg[4];
	p.light = 0;
	po = h->job.o;
	if (p.pass == PIECE_PILOT) {
		tracer_pilot_opts(&h->job.o, &po);
		p.light = po.light_paths;	/* B's statistics too */
	} else if (h->ratio) {
		po.light_ratio = h->ratio;	/* sized by the pilot */
	}
	if (p.pass != PIECE_PILOT && po.guide && !h->have_guide &&
	    tracer_pilot_wanted(&po))
		stray_error_set(&err, STRAY_EINVAL, "guide",
				"piece before the guide");
	else
		piece_run_alloc(&h->scene, &po, p.pass == PIECE_MAIN &&
				h->have_guide ? &h->guide : NULL, &p,
				&w->payload, &len, &err);
	if (err.code) {
		h->failed = 1;
		send_error(&err);
		return;
	}
	MPI_Send(w->payload, (int)len, MPI_DOUBLE, 0, TAG_RESULT,
		 MPI_COMM_WORLD);
}

int farm_serve(void)
{
	struct worker w;

	memset(&w, 0, sizeof(w));
	for (;;) {
		MPI_Status st;
		int len, id = -1;

		/* a blocking wait, not a poll with 1 ms naps: measured on 2
		 * ranks (64-design sweep, 4 alternating pairs) 0.975 of the
		 * wall and 0.977 of the CPU time.  Rank 0 still polls: it
		 * must also hear its own thread, which cannot call MPI
		 * (MPI_THREAD_FUNNELED) */
		MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
		MPI_Get_count(&st, MPI_BYTE, &len);
		switch (st.MPI_TAG) {
		case TAG_JOB:
			start_job(&w, len);
			break;
		case TAG_GUIDE:
			take_guide(&w, len);
			break;
		case TAG_TASK:
			run_task(&w);
			break;
		case TAG_ENDJOB:
			MPI_Recv(&id, 1, MPI_INT, 0, TAG_ENDJOB,
				 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
			drop(&w, id);
			break;
		case TAG_QUIT:
		default:
			MPI_Recv(NULL, 0, MPI_BYTE, 0, st.MPI_TAG,
				 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
			while (w.n)
				drop(&w, w.t[0]->job.id);
			free(w.t);
			free(w.payload);
			return 0;
		}
	}
}
