/*
 * candidates.h - the fits of one greedy forward step, on both cores
 * (candidates.c; private to diagnose/, used by run.c).
 */
#ifndef DIAGNOSE_CANDIDATES_H
#define DIAGNOSE_CANDIDATES_H

#include <pthread.h>

#include "diagnose/diag_fit.h"

struct diag_candidate {
	struct diag_fit f;	/* in: the current causes + one; out: fitted */
	int combined;		/* in: its grid joins another re-trace axis */
	int screened;		/* out: left by the screen (not traced) */
	double screen_bic;	/* out: BIC with the interaction neglected */
};

/* Fit every candidate (from the current fit of BIC bic_cur, warm); the
 * same results, bit for bit, as one after the other in order. */
int diag_fit_candidates(struct diag_eval *e, const struct diag_data *d,
			double bic_cur, struct diag_candidate *c, int n,
			struct stray_error *err);

/* Each cause alone: the fits needing no trace of their own (c, n, from
 * their grids) on a second thread while the caller traces the others;
 * finish joins it (always call it, with the caller's status rc) and fits
 * on the caller's thread, in order, those that needed a trace.  The same
 * results, bit for bit, as one after the other. */
#define DIAG_ASIDE_TRACES 256	/* cache room: the caller's traces meanwhile */
struct queue;
struct worker;
struct diag_aside {
	struct queue *q;
	struct worker *w;
	pthread_t th;
	int started, deferred[DIAG_CAUSES_MAX];
};
int diag_aside_start(struct diag_aside *a, struct diag_eval *e,
		     const struct diag_data *d, struct diag_candidate *c,
		     int n, struct stray_error *err);
int diag_aside_finish(struct diag_aside *a, struct diag_eval *e,
		      const struct diag_data *d, struct diag_candidate *c,
		      int n, int rc, struct stray_error *err);

#endif /* DIAGNOSE_CANDIDATES_H */
