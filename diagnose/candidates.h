/*
 * candidates.h - the fits of one greedy forward step, on both cores
 * (candidates.c; private to diagnose/, used by run.c).
 */
#ifndef DIAGNOSE_CANDIDATES_H
#define DIAGNOSE_CANDIDATES_H

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

#endif /* DIAGNOSE_CANDIDATES_H */
