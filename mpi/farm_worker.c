/*
 * farm_worker.c - a rank other than 0: build each job's scene from its
 * description, trace the pieces it is handed, send the payloads back.
 */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "farm_proto.h"
#include "stray/errfmt.h"
#include "tracer/scene_load.h"

struct worker {
	char *job_buf;
	struct farm_job job;
	struct tracer_scene scene;
	struct tracer_lens lens;
	struct tracer_guide guide;
	int have_scene, have_guide, failed;
	double *payload;
};

static void send_error(const struct stray_error *err)
{
	char line[200];

	stray_error_format(err, line, sizeof(line));
	MPI_Send(line, (int)strlen(line) + 1, MPI_CHAR, 0, TAG_ERROR,
		 MPI_COMM_WORLD);
}

static void end_job(struct worker *w)
{
	if (w->have_scene) {
		tracer_scene_free(&w->scene);
		tracer_lens_free(&w->lens);
	}
	free(w->job_buf);
	w->job_buf = NULL;
	w->have_scene = w->have_guide = w->failed = 0;
}

static void start_job(struct worker *w, int len)
{
	struct stray_error err;
	int rc;

	end_job(w);
	stray_error_clear(&err);
	w->job_buf = malloc(len > 0 ? (size_t)len : 1);
	MPI_Recv(w->job_buf, len, MPI_BYTE, 0, TAG_JOB, MPI_COMM_WORLD,
		 MPI_STATUS_IGNORE);
	rc = farm_job_unpack(w->job_buf, (size_t)len, &w->job, &err);
	memset(&w->lens, 0, sizeof(w->lens));
	tracer_scene_init(&w->scene);
	w->have_scene = 1;
	if (!rc)
		rc = tracer_scene_load(w->job.scene, w->job.sets,
				       w->job.n_sets, &w->scene, &err);
	if (!rc) {	/* the edits rank 0 made after loading */
		struct tracer_scene_spec ed = { w->job.scene, w->job.sets,
			w->job.n_sets, w->job.lens, w->job.beam_shift_z,
			w->job.abg_g };

		tracer_scene_spec_edit(&ed, &w->scene);
	}
	if (!rc && w->job.lens)
		rc = tracer_lens_load(w->job.lens, &w->lens, &err);
	if (!rc)
		rc = tracer_scene_commit(&w->scene, &err);
	w->job.o.lens = w->job.lens ? &w->lens : NULL;
	if (rc) {
		w->failed = 1;
		send_error(&err);
	}
}

static void run_task(struct worker *w)
{
	struct tracer_trace_opts po;
	struct stray_error err;
	struct piece p;
	int msg[4];
	size_t len = 0;

	MPI_Recv(msg, 4, MPI_INT, 0, TAG_TASK, MPI_COMM_WORLD,
		 MPI_STATUS_IGNORE);
	if (w->failed)	/* the error is on its way; rank 0 will abort */
		return;
	p.pass = msg[0];
	p.batch = msg[1];
	p.theta_first = msg[2];
	p.theta_n = msg[3];
	stray_error_clear(&err);
	po = w->job.o;
	if (p.pass == PIECE_PILOT)
		tracer_pilot_opts(&w->job.o, &po);
	if (p.pass != PIECE_PILOT && po.guide && !w->have_guide &&
	    tracer_pilot_wanted(&po))
		stray_error_set(&err, STRAY_EINVAL, "guide",
				"piece before the guide");
	else
		piece_run_alloc(&w->scene, &po, w->have_guide ? &w->guide :
				NULL, &p, &w->payload, &len, &err);
	if (err.code) {
		w->failed = 1;
		send_error(&err);
		return;
	}
	MPI_Send(w->payload, (int)len, MPI_DOUBLE, 0,
		 TAG_RESULT, MPI_COMM_WORLD);
}

int farm_serve(void)
{
	struct worker w;

	memset(&w, 0, sizeof(w));
	for (;;) {
		MPI_Status st;
		int flag = 0, len;

		MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
		if (!flag) {
			farm_nap();
			continue;
		}
		MPI_Get_count(&st, MPI_BYTE, &len);
		switch (st.MPI_TAG) {
		case TAG_JOB:
			start_job(&w, len);
			break;
		case TAG_GUIDE:
			MPI_Recv(&w.guide, (int)sizeof(w.guide), MPI_BYTE, 0,
				 TAG_GUIDE, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
			w.have_guide = 1;
			break;
		case TAG_TASK:
			run_task(&w);
			break;
		case TAG_ENDJOB:
		case TAG_QUIT:
		default:
			MPI_Recv(NULL, 0, MPI_BYTE, 0, st.MPI_TAG,
				 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
			end_job(&w);
			if (st.MPI_TAG != TAG_ENDJOB) {
				free(w.payload);
				return 0;
			}
		}
	}
}
