/*
 * lm.c - Levenberg-Marquardt for a few bounded parameters (Marquardt 1963;
 * Press et al., Numerical Recipes, §15.5): forward-difference Jacobian
 * (smooth because every trace shares one seed), steps clamped to the
 * bounds, damping adapted by success.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "diagnose/diag_fit.h"
#include "stray/errfmt.h"

#define LM_ITER_MAX 40
#define LM_STEP_REL 1e-3	/* Jacobian step, fraction of the range */

/* Solve the n x n system a x = b (a, b destroyed); 0 when singular. */
static int solve(double *a, double *b, double *x, int n)
{
	int i, j, k;

	for (k = 0; k < n; k++) {
		int piv = k;

		for (i = k + 1; i < n; i++)
			if (fabs(a[i * n + k]) > fabs(a[piv * n + k]))
				piv = i;
		if (!(fabs(a[piv * n + k]) > 0.0))
			return 0;
		for (j = 0; j < n; j++) {
			double t = a[k * n + j];

			a[k * n + j] = a[piv * n + j];
			a[piv * n + j] = t;
		}
		{
			double t = b[k];

			b[k] = b[piv];
			b[piv] = t;
		}
		for (i = k + 1; i < n; i++) {
			double f = a[i * n + k] / a[k * n + k];

			for (j = k; j < n; j++)
				a[i * n + j] -= f * a[k * n + j];
			b[i] -= f * b[k];
		}
	}
	for (i = n - 1; i >= 0; i--) {
		double s = b[i];

		for (j = i + 1; j < n; j++)
			s -= a[i * n + j] * x[j];
		x[i] = s / a[i * n + i];
	}
	return 1;
}

static double sumsq(const double *r, size_t n)
{
	double s = 0.0;
	size_t i;

	for (i = 0; i < n; i++)
		s += r[i] * r[i];
	return s;
}

static int jacobian(diag_resid_fn fn, void *user, int n_p, size_t n_r,
		    const double *p, const double *lo, const double *hi,
		    const double *r, double *J, double *r2,
		    struct stray_error *err)
{
	double q[DIAG_FIT_PMAX];
	size_t i;
	int k, rc;

	for (k = 0; k < n_p; k++) {
		double h = LM_STEP_REL * (hi[k] - lo[k]);

		memcpy(q, p, n_p * sizeof(*q));
		if (q[k] + h > hi[k])
			h = -h;
		q[k] += h;
		rc = fn(user, q, r2, err);
		if (rc)
			return rc;
		for (i = 0; i < n_r; i++)
			J[i * n_p + k] = (r2[i] - r[i]) / h;
	}
	return STRAY_OK;
}

/* The normal equations J^T J and -J^T r. */
static void normal_eq(const double *J, const double *r, int n_p, size_t n_r,
		      double *A, double *g)
{
	size_t m;
	int i, j;

	for (i = 0; i < n_p; i++) {
		g[i] = 0.0;
		for (m = 0; m < n_r; m++)
			g[i] -= J[m * n_p + i] * r[m];
		for (j = 0; j < n_p; j++) {
			A[i * n_p + j] = 0.0;
			for (m = 0; m < n_r; m++)
				A[i * n_p + j] += J[m * n_p + i] * J[m * n_p + j];
		}
	}
}

struct lm_ctx {
	diag_resid_fn fn;
	void *user;
	int n_p;
	size_t n_r;
	const double *lo, *hi;
	double lambda;
};

/*
 * One damped step from p (residuals r, sum c): raise lambda until a step
 * lowers the sum or lambda runs away.  1 when p, r and *c were improved.
 */
static int lm_step(struct lm_ctx *x, const double *A, const double *g,
		   double *p, double *r, double *rt, double *c,
		   struct stray_error *err, int *rc)
{
	double A2[DIAG_FIT_PMAX * DIAG_FIT_PMAX], g2[DIAG_FIT_PMAX];
	double dx[DIAG_FIT_PMAX], q[DIAG_FIT_PMAX], ct;
	int k, n = x->n_p;

	while (x->lambda < 1e10) {
		memcpy(A2, A, (size_t)n * n * sizeof(*A2));
		memcpy(g2, g, (size_t)n * sizeof(*g2));
		for (k = 0; k < n; k++)	/* Marquardt's scaling, plus a floor */
			A2[k * n + k] = A2[k * n + k] * (1.0 + x->lambda) + 1e-12;
		if (!solve(A2, g2, dx, n)) {
			x->lambda *= 10.0;
			continue;
		}
		for (k = 0; k < n; k++)
			q[k] = fmin(fmax(p[k] + dx[k], x->lo[k]), x->hi[k]);
		*rc = x->fn(x->user, q, rt, err);
		if (*rc)
			return 0;
		ct = sumsq(rt, x->n_r);
		if (ct < *c) {
			memcpy(p, q, (size_t)n * sizeof(*p));
			memcpy(r, rt, x->n_r * sizeof(*r));
			x->lambda = fmax(x->lambda / 10.0, 1e-7);
			*c = ct;
			return 1;
		}
		x->lambda *= 10.0;
	}
	return 0;
}

int diag_lm(diag_resid_fn fn, void *user, int n_p, size_t n_r, double *p,
	    const double *lo, const double *hi, double *chi2,
	    struct stray_error *err)
{
	struct lm_ctx x = { fn, user, n_p, n_r, lo, hi, 1e-3 };
	double *r = malloc(3 * n_r * sizeof(*r)), *rt, *r2, *J, c;
	int it, rc;

	J = malloc((n_r * (n_p ? n_p : 1)) * sizeof(*J));
	if (!r || !J) {
		free(r);
		free(J);
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	}
	rt = r + n_r;
	r2 = rt + n_r;
	rc = fn(user, p, r, err);
	c = sumsq(r, n_r);
	for (it = 0; !rc && n_p > 0 && it < LM_ITER_MAX; it++) {
		double A[DIAG_FIT_PMAX * DIAG_FIT_PMAX], g[DIAG_FIT_PMAX];
		double before = c;

		rc = jacobian(fn, user, n_p, n_r, p, lo, hi, r, J, r2, err);
		if (rc)
			break;
		normal_eq(J, r, n_p, n_r, A, g);
		if (!lm_step(&x, A, g, p, r, rt, &c, err, &rc))
			break;
		if (before - c < 1e-6 * (1.0 + before))
			break;	/* converged */
	}
	*chi2 = c;
	free(r);
	free(J);
	return rc;
}
