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
	int *deferred, rc;
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
		   double bic_cur, struct diag_candidate *c,
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
	return diag_fit_run(e, d, &c->f, 1, err);
}

static void *work(void *arg)
{
	struct worker *w = arg;
	int i;

	while (!w->rc && (i = take(w->q)) >= 0) {
		struct diag_candidate keep = w->c[i];

		w->e.missed = 0;
		w->rc = fit_one(&w->e, w->d, w->bic_cur, &w->c[i], &w->err);
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

int diag_fit_candidates(struct diag_eval *e, const struct diag_data *d,
			double bic_cur, struct diag_candidate *c, int n,
			struct stray_error *err)
{
	struct worker w[2];
	struct queue q = { PTHREAD_MUTEX_INITIALIZER, 0, n };
	pthread_t th;
	int deferred[DIAG_CAUSES_MAX] = { 0 }, i, k, started, rc = STRAY_OK;

	(void)diag_band_current();	/* loaded once, before the threads */
	for (k = 0; k < 2; k++) {
		w[k].e = *e;
		w[k].e.chol_in = w[k].e.chol_out = w[k].e.blend_alpha = NULL;
		w[k].e.chol_n = 0;
		w[k].e.no_trace = 1;
		w[k].d = d;
		w[k].bic_cur = bic_cur;
		w[k].c = c;
		w[k].q = &q;
		w[k].deferred = deferred;
		w[k].rc = STRAY_OK;
		stray_error_clear(&w[k].err);
	}
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
			rc = fit_one(e, d, bic_cur, &c[i], err);
	return rc;
}
