/*
 * farm_set.c - the traces in flight, their one queue of pieces, and rank
 * 0's own worker thread (farm_set.h).  No MPI here.
 */
#include <stdlib.h>
#include <string.h>

#include "farm_set.h"
#include "tracer/scene_load.h"

struct farm_config farm_config = { 0, 300.0, 0 };
struct farm_stats farm_last;

/* Angle chunks of a pass: one (the paths serve every angle; a chunk
 * retraces them) unless all the traces' batches cannot give each rank
 * about 2 pieces (the cost model, bench/mpi_model.awk: 2 rather than 4
 * retraces less and balances as well; 64-design sweep at 256 ranks 0.91
 * against 0.87, the curve at 16 ranks 0.76 against 0.69). */
static int chunks_for(const struct tracer_trace_opts *po, size_t n_traces,
		      int size)
{
	size_t batches = (size_t)po->n_batches * n_traces;
	int c = farm_config.angle_chunks;

	if (c <= 0)
		c = (int)((2 * (size_t)size + batches - 1) / batches);
	if ((size_t)c > po->n_theta)
		c = (int)po->n_theta;
	return c < 1 ? 1 : c;
}

int farm_set_init(struct farm_set *fs, const struct tracer_trace_item *items,
		  size_t n, const struct tracer_scene *scene, int size,
		  farm_done_fn done, void *user, struct stray_error *err)
{
	struct tracer_trace_opts po;
	size_t i;

	memset(fs, 0, sizeof(*fs));
	fs->n = n;
	fs->size = size;
	fs->done = done;
	fs->user = user;
	fs->t = calloc(n ? n : 1, sizeof(*fs->t));
	fs->held = calloc((size_t)size * (n ? n : 1), 1);
	if (!fs->t || !fs->held) {
		free(fs->t);
		free(fs->held);
		return stray_error_set(err, STRAY_ENOMEM, "mpi",
				       "out of memory");
	}
	for (i = 0; i < n; i++) {
		fs->t[i].spec = items[i].spec;
		fs->t[i].o = items[i].o;
		fs->t[i].scene = scene;
		tracer_scene_init(&fs->t[i].own);
	}
	if (n) {	/* the traces of a set share their options' shape */
		tracer_pilot_opts(items[0].o, &po);
		fs->chunks[PIECE_PILOT] = chunks_for(&po, n, size);
		fs->chunks[PIECE_MAIN] = chunks_for(items[0].o, n, size);
	}
	pthread_mutex_init(&fs->lock, NULL);
	pthread_cond_init(&fs->wake, NULL);
	stray_error_clear(&fs->err);
	return STRAY_OK;
}

static void free_pass(struct farm_pass *p)
{
	int b;

	if (p->tables)
		for (b = 0; b < p->o.n_batches; b++)
			tracer_paths_free(&p->tables[b]);
	free(p->tables);
	free(p->plan);
	free(p->s2);
	free(p->light);
	tracer_result_free(&p->r);
	memset(p, 0, sizeof(*p));
}

static void free_trace(struct farm_trace *t)
{
	free_pass(&t->pass[PIECE_PILOT]);
	free_pass(&t->pass[PIECE_MAIN]);
	free(t->g);
	t->g = NULL;
	free(t->ratio);
	t->ratio = NULL;
	if (t->own_built)
		tracer_scene_free(&t->own);
	t->own_built = 0;
}

void farm_set_free(struct farm_set *fs)
{
	size_t i;

	for (i = 0; i < fs->n; i++)
		free_trace(&fs->t[i]);
	free(fs->t);
	free(fs->held);
	pthread_mutex_destroy(&fs->lock);
	pthread_cond_destroy(&fs->wake);
}

static int fail(struct farm_set *fs, int code, const char *text)
{
	if (!fs->failed)
		stray_error_set(&fs->err, code, "mpi", text);
	fs->failed = 1;
	pthread_cond_broadcast(&fs->wake);
	return fs->err.code ? fs->err.code : STRAY_EIO;
}

/* A pass's plan and empty result (and the pilot's s2, the tables). */
static int open_pass(struct farm_set *fs, struct farm_trace *t, int pass)
{
	struct farm_pass *p = &t->pass[pass];
	int chunks = fs->chunks[pass];

	if (pass == PIECE_PILOT)
		tracer_pilot_opts(t->o, &p->o);
	else
		p->o = *t->o;
	p->plan = malloc((size_t)p->o.n_batches * (size_t)chunks *
			 sizeof(*p->plan));
	if (!p->plan || piece_result_alloc(&p->o, &p->r, pass == PIECE_PILOT ?
					   &p->s2 : NULL))
		return fail(fs, STRAY_ENOMEM, "out of memory");
	if (p->o.record_paths && !(p->tables = calloc((size_t)p->o.n_batches,
						      sizeof(*p->tables))))
		return fail(fs, STRAY_ENOMEM, "out of memory");
	p->n_plan = piece_plan(pass, p->o.n_batches, p->o.n_theta, chunks,
			       p->plan);
	if (pass == PIECE_PILOT && p->o.light_paths) {	/* B's statistics */
		size_t k;

		p->light = calloc((size_t)p->o.n_batches * p->o.n_theta *
				  TRACER_LIGHT_STATS, sizeof(double));
		if (!p->light)
			return fail(fs, STRAY_ENOMEM, "out of memory");
		for (k = 0; k < p->n_plan; k++)
			p->plan[k].light = 1;
	}
	*(pass == PIECE_PILOT ? &farm_last.pilot_tasks : &farm_last.tasks) +=
		p->n_plan;
	return STRAY_OK;
}

/* A set's trace is checked as it opens, on rank 0 (its scene loaded, no
 * commit: ~0.4 ms for ref4; the first one committed and the options
 * checked too): a bad design is named as `stray sweep` names it, and
 * the set stops before any rank is handed its pieces. */
static int check_trace(struct farm_set *fs, struct farm_trace *t)
{
	struct tracer_scene s;
	struct stray_error e;
	double t0 = farm_now();
	int rc;

	stray_error_clear(&e);
	tracer_scene_init(&s);
	rc = tracer_scene_load(t->spec.scene, t->spec.sets, t->spec.n_sets,
			       &s, &e);
	if (!rc && t == fs->t) {
		tracer_scene_spec_edit(&t->spec, &s);
		rc = tracer_scene_commit(&s, &e);
		if (!rc)
			rc = tracer_trace_check(&s, t->o, &e);
		farm_last.start_s = farm_now() - t0;
	}
	tracer_scene_free(&s);
	if (rc && !fs->failed) {
		fs->err = e;
		fs->failed = 1;
		pthread_cond_broadcast(&fs->wake);
	}
	return rc;
}

static int open_trace(struct farm_set *fs, struct farm_trace *t)
{
	if (!t->scene && check_trace(fs, t))
		return STRAY_EINVAL;
	t->t0 = farm_now();
	if (tracer_pilot_wanted(t->o)) {
		t->phase = FT_PILOT;
		return open_pass(fs, t, PIECE_PILOT) ||
		       open_pass(fs, t, PIECE_MAIN);
	}
	t->phase = FT_MAIN;
	return open_pass(fs, t, PIECE_MAIN);
}

/* The pass of trace t with a piece free now, or -1. */
static int free_pass_of(const struct farm_trace *t)
{
	int pass = t->phase == FT_PILOT ? PIECE_PILOT :
		   t->phase == FT_MAIN ? PIECE_MAIN : -1;

	if (pass < 0 || t->pass[pass].next >= t->pass[pass].n_plan)
		return -1;
	return pass;
}

static void give(struct farm_set *fs, int rank, size_t i, int pass,
		 struct farm_take *out)
{
	unsigned char *h = &fs->held[(size_t)rank * fs->n + i];

	out->trace = i;
	out->pass = pass;
	out->k = fs->t[i].pass[pass].next++;
	out->send_job = !(*h & HELD_JOB);
	out->send_guide = pass == PIECE_MAIN && fs->t[i].g &&
			  !(*h & HELD_GUIDE);
	*h |= HELD_JOB | (pass == PIECE_MAIN && fs->t[i].g ? HELD_GUIDE : 0);
}

/* Pieces of trace t free now. */
static size_t n_free(const struct farm_trace *t)
{
	int pass = free_pass_of(t);

	return pass < 0 ? 0 : t->pass[pass].n_plan - t->pass[pass].next;
}

/* held_only: the oldest live trace whose scene this rank built with a
 * piece free; else the trace with the most pieces free (the rank then
 * stays long on the scene it builds).  Its pass in *pass; -1: none. */
static long first_free(const struct farm_set *fs, int rank, int held_only,
		       int *pass)
{
	size_t i, most = 0;
	long pick = -1;

	for (i = fs->first_live; i < fs->n_open; i++) {
		size_t k;

		if (held_only &&
		    !(fs->held[(size_t)rank * fs->n + i] & HELD_JOB))
			continue;
		k = n_free(&fs->t[i]);
		if (k > most) {
			most = k;
			pick = (long)i;
			if (held_only)
				break;
		}
	}
	if (pick >= 0)
		*pass = free_pass_of(&fs->t[pick]);
	return pick;
}

int farm_set_take(struct farm_set *fs, int rank, struct farm_take *out)
{
	long i;
	int pass;

	if (fs->failed || fs->quit)
		return 0;
	/* a trace whose scene this rank built (the oldest first); else a new
	 * trace (one scene build, as joining another would cost, and the
	 * ranks spread over the designs); else join the trace in flight with
	 * the most pieces free */
	i = first_free(fs, rank, 1, &pass);
	if (i < 0 && fs->n_open < fs->n) {
		i = (long)fs->n_open++;
		if (open_trace(fs, &fs->t[i]))
			return 0;
		pthread_cond_broadcast(&fs->wake);
		if ((pass = free_pass_of(&fs->t[i])) < 0)
			i = -1;
	}
	if (i < 0)
		i = first_free(fs, rank, 0, &pass);
	if (i < 0)
		return 0;
	give(fs, rank, (size_t)i, pass, out);
	return 1;
}

const struct piece *farm_set_piece(const struct farm_set *fs,
				   const struct farm_take *t)
{
	return &fs->t[t->trace].pass[t->pass].plan[t->k];
}

/* The pilot is in: the guide, as tracer_trace builds it (and with
 * light_paths B's ratios from the same pilot, tracer/batches.h), then the
 * main pass is free to go. */
static int pilot_done(struct farm_set *fs, struct farm_trace *t)
{
	struct farm_pass *p = &t->pass[PIECE_PILOT];

	t->g = malloc(sizeof(*t->g));
	if (!t->g || tracer_guide_from_pilot(t->g, &p->r, p->s2))
		return fail(fs, STRAY_ENOMEM, "out of memory");
	if (p->light) {
		t->ratio = malloc(p->o.n_theta * sizeof(double));
		if (!t->ratio)
			return fail(fs, STRAY_ENOMEM, "out of memory");
		tracer_light_alloc(&p->r, p->light, t->ratio);
		t->pass[PIECE_MAIN].o.light_ratio = t->ratio;
	}
	free_pass(p);
	t->phase = FT_MAIN;
	pthread_cond_broadcast(&fs->wake);
	return STRAY_OK;
}

/* The batches' path records into the result in batch order, as
 * tracer_trace() merges them: the same sums, bit for bit. */
static int main_done(struct farm_set *fs, struct farm_trace *t)
{
	struct farm_pass *p = &t->pass[PIECE_MAIN];
	int b;

	for (b = 0; p->tables && b < p->o.n_batches; b++)
		if (tracer_paths_merge(&p->r.paths, &p->tables[b]))
			return fail(fs, STRAY_ENOMEM,
				    "out of memory recording paths");
	t->seconds = farm_now() - t->t0;
	t->phase = FT_DONE;
	return STRAY_OK;
}

int farm_set_apply(struct farm_set *fs, const struct farm_take *tk,
		   const double *payload)
{
	struct farm_trace *t = &fs->t[tk->trace];
	struct farm_pass *p = &t->pass[tk->pass];
	const struct piece *pc = &p->plan[tk->k];

	if (fs->failed)		/* the set stops: pieces still out are dropped */
		return STRAY_OK;
	piece_apply(pc, payload, &p->r, p->s2, p->light);
	if (p->tables && piece_apply_paths(pc, payload, p->tables))
		return fail(fs, STRAY_ENOMEM, "out of memory recording paths");
	if (++p->done < p->n_plan)
		return STRAY_OK;
	return tk->pass == PIECE_PILOT ? pilot_done(fs, t) : main_done(fs, t);
}

int farm_set_finished(struct farm_set *fs)
{
	return fs->failed || fs->first_live == fs->n;
}

int farm_set_collect(struct farm_set *fs,
		     void (*drop)(void *ctx, int rank, size_t trace), void *ctx)
{
	size_t i;
	int r, rc = STRAY_OK;
	double t0;

	if (fs->failed)
		return STRAY_OK;
	for (i = fs->first_live; !rc && i < fs->n_open; i++) {
		struct farm_trace *t = &fs->t[i];
		struct stray_error e;

		pthread_mutex_lock(&fs->lock);
		r = t->phase == FT_DONE;
		pthread_mutex_unlock(&fs->lock);
		if (!r)
			continue;
		/* the caller's work (a design's curve) while ranks trace */
		stray_error_clear(&e);
		t->pass[PIECE_MAIN].r.seconds = t->seconds;
		t0 = farm_now();
		rc = fs->done(fs->user, i, &t->pass[PIECE_MAIN].r, &e);
		farm_last.done_s += farm_now() - t0;
		for (r = 1; r < fs->size; r++)
			if (fs->held[(size_t)r * fs->n + i] & HELD_JOB)
				drop(ctx, r, i);
		pthread_mutex_lock(&fs->lock);
		free_trace(t);
		t->phase = FT_OVER;
		if (rc && !fs->failed) {
			fs->err = e;
			fs->failed = 1;
			pthread_cond_broadcast(&fs->wake);
		}
		while (fs->first_live < fs->n &&
		       fs->t[fs->first_live].phase == FT_OVER)
			fs->first_live++;
		if (fs->first_live == fs->n)
			pthread_cond_broadcast(&fs->wake);
		pthread_mutex_unlock(&fs->lock);
	}
	return rc;
}

/* Rank 0's thread: the scene of trace t, built on first use. */
static int local_scene(struct farm_trace *t, struct stray_error *err)
{
	double t0 = farm_now();
	int rc;

	if (t->scene)
		return STRAY_OK;
	rc = tracer_scene_load(t->spec.scene, t->spec.sets, t->spec.n_sets,
			       &t->own, err);
	if (!rc) {
		tracer_scene_spec_edit(&t->spec, &t->own);
		rc = tracer_scene_commit(&t->own, err);
	}
	t->own_built = 1;	/* freed with the trace, even half built */
	farm_last.local_builds++;	/* this thread's alone */
	farm_last.local_build_s += farm_now() - t0;
	if (!rc)
		t->scene = &t->own;
	return rc;
}

void *farm_set_local(void *arg)
{
	struct farm_set *fs = arg;
	double *buf = NULL;
	size_t len;

	pthread_mutex_lock(&fs->lock);
	while (!fs->failed && fs->first_live < fs->n) {
		struct farm_take tk;
		struct farm_trace *t;
		struct stray_error e;
		int rc;

		if (!farm_set_take(fs, 0, &tk)) {
			if (!fs->failed && fs->first_live < fs->n)
				pthread_cond_wait(&fs->wake, &fs->lock);
			continue;
		}
		t = &fs->t[tk.trace];
		pthread_mutex_unlock(&fs->lock);
		stray_error_clear(&e);
		rc = local_scene(t, &e);
		if (!rc)
			rc = piece_run_alloc(t->scene, &t->pass[tk.pass].o,
					     tk.pass == PIECE_MAIN ? t->g : NULL,
					     farm_set_piece(fs, &tk), &buf,
					     &len, &e);
		pthread_mutex_lock(&fs->lock);
		if (!rc)
			rc = farm_set_apply(fs, &tk, buf);
		if (rc && !fs->failed) {
			fs->err = e;
			fs->failed = 1;
			pthread_cond_broadcast(&fs->wake);
		}
	}
	pthread_mutex_unlock(&fs->lock);
	free(buf);
	return NULL;
}
