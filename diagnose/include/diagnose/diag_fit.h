/*
 * diag_fit.h - the fit of causes to a measured curve: weighted least
 * squares of log10 residuals (Levenberg-Marquardt on bounded
 * parameters), BIC, profile-chi2 intervals.
 */
#ifndef DIAGNOSE_DIAG_FIT_H
#define DIAGNOSE_DIAG_FIT_H

#include <stddef.h>

#include "diagnose/diag_cause.h"
#include "diagnose/diag_data.h"
#include "diagnose/diag_eval.h"
#include "stray/error.h"

#define DIAG_COMBO_MAX 3	/* causes named together at most */
#define DIAG_FIT_PMAX (DIAG_PARAMS_MAX * DIAG_COMBO_MAX)

struct diag_fit {
	int n_causes;
	const struct diag_cause *cause[DIAG_COMBO_MAX];
	int n_p;
	double p[DIAG_FIT_PMAX];
	double ci_lo[DIAG_FIT_PMAX], ci_hi[DIAG_FIT_PMAX];
	double chi2, bic;
	int k;
	int converged;
};

/* chi2 of the state's model against the data, measurement errors and the
 * correlated simulation errors combined; resid, resid_sigma (diagonal),
 * model and white (whitened residuals, chi2 = |white|^2) may be NULL. */
int diag_chi2(struct diag_eval *e, const struct diag_data *d,
	      const struct diag_state *s, double *chi2, double *resid,
	      double *resid_sigma, double *model, double *white,
	      struct stray_error *err);

/* The state of a fit's causes at parameters p. */
void diag_fit_state(const struct diag_fit *f, const double *p,
		    struct diag_state *s);

/* Fit the causes already set in f (their parameters), from the starts
 * in f->p when warm, else from each cause's coarse grid. */
int diag_fit_run(struct diag_eval *e, const struct diag_data *d,
		 struct diag_fit *f, int warm, struct stray_error *err);

/* Profile-chi2 intervals: delta chi2 = DIAG_CI_DCHI2 max(1, reduced
 * chi2); 9 is the 3-sigma (99.7 %) interval of one parameter. */
#define DIAG_CI_DCHI2 9.0
int diag_fit_intervals(struct diag_eval *e, const struct diag_data *d,
		       struct diag_fit *f, struct stray_error *err);

/* Levenberg-Marquardt on bounded parameters (lm.c). */
typedef int (*diag_resid_fn)(void *user, const double *p, double *r,
			     struct stray_error *err);
int diag_lm(diag_resid_fn fn, void *user, int n_p, size_t n_r, double *p,
	    const double *lo, const double *hi, double *chi2,
	    struct stray_error *err);

#endif /* DIAGNOSE_DIAG_FIT_H */
