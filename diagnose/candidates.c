/*
 * candidates.c - the fits of one greedy forward step (run.c), on both
 * cores.  The candidates' fits are independent given the traces they
 * read, so two threads fit them side by side, each with its own copy of
 * the evaluator (its own last blend and Cholesky factor) over the shared
 * trace cache, read only: a fit that needs a trace not cached yet stops
 * and is fitted again afterwards, in candidate order, on the caller's
 * thread, which alone traces (through the caller's runner: stray-mpi's
 * farm is driven from one thread).  The traces are then made in the
 * order a serial step would make them, and every fit reads the same
 * traces and computes the same bits (the evaluator's kept blend and
 * factor are exact): the step's result does not depend on the threads.
 */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "candidates.h"
#include "trace_cache.h"
#include "diagnose/diag_result.h"
#include "diagnose/diag_spectral.h"
#include "stray/errfmt.h"

/* The next candidate to fit, taken by whichever thread is free (one
 * candidate, a leak beside a two-parameter coating, can take as long as
 * the rest together). */
struct queue {
	pthread_mutex_t lock;
	int next, n;
};

struct worker {
	struct diag_eval e;	/* a copy: own caches, no tracing */
	const struct diag_data *d;
	double bic_cur;
	struct diag_candidate *c;
	struct queue *q;
	int warm, *deferred, rc;
	struct stray_error err;
};

static int take(struct queue *q)
{
	int i;

	pthread_mutex_lock(&q->lock);
	i = q->next < q->n ? q->next++ : -1;
	pthread_mutex_unlock(&q->lock);
	return i;
}

/* The screen (run.c): fitted with the interaction neglected first; only
 * a candidate lowering BIC by half the margin that way is fitted on its
 * combined grid. */
static int fit_one(struct diag_eval *e, const struct diag_data *d,
		   double bic_cur, int warm, struct diag_candidate *c,
		   struct stray_error *err)
{
	int rc;

	c->screened = 0;
	if (c->combined) {
		struct diag_fit g = c->f;
		const struct diag_cause *x = g.cause[g.n_causes - 1];

		e->factorized = 1u << x->geo_axis;
		rc = diag_fit_run(e, d, &g, 1, err);
		e->factorized = 0u;
		if (rc)
			return rc;
		c->screen_bic = g.bic;
		if (bic_cur - g.bic < 0.5 * DIAG_BIC_MARGIN) {
			c->screened = 1;
			return STRAY_OK;
		}
	}
	return diag_fit_run(e, d, &c->f, warm, err);
}

static void *work(void *arg)
{
	struct worker *w = arg;
	int i;

	while (!w->rc && (i = take(w->q)) >= 0) {
		struct diag_candidate keep = w->c[i];

		w->e.missed = 0;
		w->rc = fit_one(&w->e, w->d, w->bic_cur, w->warm, &w->c[i],
				&w->err);
		if (w->e.missed) {	/* a trace to make: the caller's */
			w->c[i] = keep;
			w->deferred[i] = 1;
			w->rc = STRAY_OK;
		}
	}
	free(w->e.chol_in);
	free(w->e.blend_alpha);
	return NULL;
}

/* A copy of the evaluator that fits beside the caller: its own kept
 * blend and factor, the trace cache as it is now, no tracing. */
static void worker_init(struct worker *w, const struct diag_eval *e,
			const struct diag_data *d, double bic_cur, int warm,
			struct diag_candidate *c, struct queue *q,
			int *deferred)
{
	(void)diag_band_current();	/* loaded once, before the threads */
	w->e = *e;
	w->e.chol_in = w->e.chol_out = w->e.blend_alpha = NULL;
	w->e.chol_n = 0;
	w->e.no_trace = 1;
	w->d = d;
	w->bic_cur = bic_cur;
	w->warm = warm;
	w->c = c;
	w->q = q;
	w->deferred = deferred;
	w->rc = STRAY_OK;
	stray_error_clear(&w->err);
}

int diag_fit_candidates(struct diag_eval *e, const struct diag_data *d,
			double bic_cur, struct diag_candidate *c, int n,
			struct stray_error *err)
{
	struct worker w[2];
	struct queue q = { PTHREAD_MUTEX_INITIALIZER, 0, n };
	pthread_t th;
	int deferred[DIAG_CAUSES_MAX] = { 0 }, i, k, started, rc = STRAY_OK;

	for (k = 0; k < 2; k++)
		worker_init(&w[k], e, d, bic_cur, 1, c, &q, deferred);
	started = e->fit_threads != 1 && n > 1 &&
		  pthread_create(&th, NULL, work, &w[1]) == 0;
	work(&w[0]);	/* without a second thread: all on this one */
	if (started)
		pthread_join(th, NULL);
	for (k = 0; k < 2 && !rc; k++)
		if (w[k].rc) {
			*err = w[k].err;
			rc = w[k].rc;
		}
	for (i = 0; i < n && !rc; i++)
		if (deferred[i])
			rc = fit_one(e, d, bic_cur, 1, &c[i], err);
	return rc;
}

/*
 * Each cause alone (run.c): the fits that need no trace of their own
 * (re-weighted and post-processed causes) run on a second thread while
 * the caller traces and fits the re-trace causes' grids.  The copy reads
 * the traces cached when it starts; the cache is given room first, so
 * the caller's new traces never move the list it reads.  A fit that
 * needs a trace (the angle offset's fine grid) is made by the caller
 * after, in order.
 */
int diag_aside_start(struct diag_aside *a, struct diag_eval *e,
		     const struct diag_data *d, struct diag_candidate *c,
		     int n, struct stray_error *err)
{
	int i, rc;

	memset(a->deferred, 0, sizeof(a->deferred));
	for (i = 0; i < n; i++)
		a->deferred[i] = 1;	/* unless the thread fits it */
	a->started = 0;
	a->q = malloc(sizeof(*a->q));
	a->w = malloc(sizeof(*a->w));
	if (!a->q || !a->w)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	rc = diag_trace_cache_reserve(e, DIAG_ASIDE_TRACES, err);
	if (rc || e->fit_threads == 1 || n == 0)
		return rc;
	memset(a->deferred, 0, sizeof(a->deferred));
	pthread_mutex_init(&a->q->lock, NULL);
	a->q->next = 0;
	a->q->n = n;
	worker_init(a->w, e, d, 0.0, 0, c, a->q, a->deferred);
	a->started = pthread_create(&a->th, NULL, work, a->w) == 0;
	if (!a->started)
		for (i = 0; i < n; i++)
			a->deferred[i] = 1;
	return STRAY_OK;
}

int diag_aside_finish(struct diag_aside *a, struct diag_eval *e,
		      const struct diag_data *d, struct diag_candidate *c,
		      int n, int rc, struct stray_error *err)
{
	int i;

	if (a->started) {
		pthread_join(a->th, NULL);
		pthread_mutex_destroy(&a->q->lock);
		if (!rc && a->w->rc) {
			*err = a->w->err;
			rc = a->w->rc;
		}
	}
	for (i = 0; i < n && !rc; i++)
		if (a->deferred[i])
			rc = fit_one(e, d, 0.0, 0, &c[i], err);
	free(a->q);
	free(a->w);
	a->q = NULL;
	a->w = NULL;
	return rc;
}
