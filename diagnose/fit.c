/*
 * fit.c - weighted least squares of log10 residuals for a set of causes.
 *
 * r_i = log10(measured_i / model_i), sigma_r,i = sqrt((s_m/m)^2 +
 * (s_sim/model)^2) / ln 10 (measurement and simulation errors combined,
 * first order); chi2 = sum (r / sigma_r)^2.  A fit starts from each
 * cause's coarse grid (or its own start list), keeps the best starts and
 * refines them with Levenberg-Marquardt (lm.c).  Intervals come from the
 * profile chi2: the other parameters re-fitted at each probe, the edge
 * where chi2 rises by DIAG_CI_DCHI2 max(1, reduced chi2) (Press et al.
 * §15.6; 9 = three standard deviations for one parameter of interest;
 * the scaling absorbs a model that fits worse than the stated errors).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "diagnose/diag_fit.h"
#include "stray/errfmt.h"

#define STARTS_MAX 8192
#define KEEP_STARTS 3
#define PROFILE_STEPS 14
#define MODEL_TINY 1e-30	/* a model of 0 is a huge, finite residual */

/* In-place Cholesky factor (lower) of an n x n SPD matrix; 0 if not.
 * Below the diagonal, four rows at a time: each element's sum keeps its
 * own order (the same bits as one row at a time), the four independent
 * sums hide the latency of the add that each would otherwise wait for. */
static int cholesky(double *c, size_t n)
{
	size_t i, j, k;

	for (j = 0; j < n; j++) {
		const double *cj = c + j * n;
		double s = cj[j];

		for (k = 0; k < j; k++)
			s -= cj[k] * cj[k];
		if (!(s > 0.0))
			return 0;
		c[j * n + j] = sqrt(s);
		for (i = j + 1; i + 3 < n; i += 4) {
			double *c0 = c + i * n, *c1 = c0 + n, *c2 = c1 + n,
			       *c3 = c2 + n;
			double t0 = c0[j], t1 = c1[j], t2 = c2[j], t3 = c3[j];

			for (k = 0; k < j; k++) {
				t0 -= c0[k] * cj[k];
				t1 -= c1[k] * cj[k];
				t2 -= c2[k] * cj[k];
				t3 -= c3[k] * cj[k];
			}
			c0[j] = t0 / cj[j];
			c1[j] = t1 / cj[j];
			c2[j] = t2 / cj[j];
			c3[j] = t3 / cj[j];
		}
		for (; i < n; i++) {
			double t = c[i * n + j];

			for (k = 0; k < j; k++)
				t -= c[i * n + k] * cj[k];
			c[i * n + j] = t / cj[j];
		}
	}
	return 1;
}

/*
 * Covariance of the log10 residuals, C = (diag(s_m/m)^2 + relcov) /
 * ln(10)^2 (first order), whitened through its Cholesky factor L:
 * chi2 = |L^-1 r|^2 (generalised least squares).  The factor of the last
 * C is kept, keyed by what C is made of (relcov and the measurement's
 * diagonal): relcov depends on the geometry blend and the floor/leak
 * share only, so a fit of re-weighted or post-processed causes factors
 * it once, not per evaluation (n^3 / 6 each, the fit's largest cost); the
 * same C gives the same factor, bit for bit.  Only C's lower triangle is
 * made: all the factor and the substitution read.
 */
static int whiten(struct diag_eval *e, const struct diag_data *d,
		  const double *relcov, const double *r, double *w,
		  double *diag)
{
	size_t i, k, n = d->n;
	double *key = e->chol_in, *L = e->chol_out;

	for (i = 0; i < n; i++) {
		double rm = d->sigma[i] / d->alpha[i];

		diag[i] = rm * rm;
	}
	if (e->chol_ok < 0 || memcmp(key, relcov, n * n * sizeof(*key)) ||
	    memcmp(key + n * n, diag, n * sizeof(*key))) {
		memcpy(key, relcov, n * n * sizeof(*key));
		memcpy(key + n * n, diag, n * sizeof(*key));
		for (i = 0; i < n; i++)
			for (k = 0; k <= i; k++)
				L[i * n + k] = (relcov[i * n + k] +
						(i == k ? diag[i] : 0.0)) /
					       (M_LN10 * M_LN10);
		e->chol_ok = cholesky(L, n);
	}
	if (!e->chol_ok)
		return 0;
	for (i = 0; i < n; i++) {	/* forward substitution */
		double t = r[i];

		for (k = 0; k < i; k++)
			t -= L[i * n + k] * w[k];
		w[i] = t / L[i * n + i];
	}
	return 1;
}

/* e->chol_in, one block for n: whiten's key (relcov, the diagonal), the
 * factor (e->chol_out), and diag_chi2's work (5 n + n^2) after it; made
 * once per evaluator, not per evaluation (a fit makes thousands). */
static double *chi2_work(struct diag_eval *e, size_t n)
{
	if (e->chol_n != n) {
		double *b = realloc(e->chol_in, (3 * n * n + 6 * n) *
					       sizeof(*b));

		if (!b)
			return NULL;
		e->chol_in = b;
		e->chol_out = b + n * n + n;
		e->chol_n = n;
		e->chol_ok = -1;	/* no factor kept */
	}
	return e->chol_out + n * n;
}

int diag_chi2(struct diag_eval *e, const struct diag_data *d,
	      const struct diag_state *s, double *chi2, double *resid,
	      double *resid_sigma, double *model, double *white,
	      struct stray_error *err)
{
	size_t i, n = d->n;
	double *a = chi2_work(e, n);
	double *sg, *r, *w, *dg, *rel, c = 0.0;
	int rc;

	if (!a)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	sg = a + n;
	r = sg + n;
	w = r + n;
	dg = w + n;
	rel = dg + n;
	rc = diag_eval_model(e, s, a, sg, rel, err);
	for (i = 0; !rc && i < n; i++) {
		double m = fmax(a[i], MODEL_TINY);
		double rm = d->sigma[i] / d->alpha[i], rs = sg[i] / m;

		r[i] = log10(d->alpha[i] / m);
		if (resid)
			resid[i] = r[i];
		if (resid_sigma)
			resid_sigma[i] = sqrt(rm * rm + rs * rs) / M_LN10;
		if (model)
			model[i] = a[i];
	}
	if (!rc && !whiten(e, d, rel, r, w, dg))
		for (i = 0; i < n; i++)	/* not SPD: the diagonal alone */
			w[i] = r[i] / (sqrt(fmax(rel[i * n + i], 0.0) +
				pow(d->sigma[i] / d->alpha[i], 2)) / M_LN10);
	for (i = 0; !rc && i < n; i++) {
		c += w[i] * w[i];
		if (white)
			white[i] = w[i];
	}
	*chi2 = c;
	return rc;
}

void diag_fit_state(const struct diag_fit *f, const double *p,
		    struct diag_state *s)
{
	int c, o = 0;

	diag_state_nominal(s);
	for (c = 0; c < f->n_causes; c++) {
		f->cause[c]->apply(p + o, s);
		o += f->cause[c]->n_params;
	}
}

static void fit_bounds(const struct diag_fit *f, double *lo, double *hi)
{
	int c, k, o = 0;

	for (c = 0; c < f->n_causes; c++)
		for (k = 0; k < f->cause[c]->n_params; k++, o++) {
			lo[o] = f->cause[c]->param[k].lo;
			hi[o] = f->cause[c]->param[k].hi;
		}
}

struct resid_ctx {
	struct diag_eval *e;
	const struct diag_data *d;
	const struct diag_fit *f;
	int fixed;		/* profile: index of a held parameter, or -1 */
	double fixed_value;
	double *full;		/* scratch: all parameters */
};

static int resid_fn(void *user, const double *p, double *r,
		    struct stray_error *err)
{
	struct resid_ctx *x = user;
	struct diag_state s;
	double chi2;
	int i, k;

	for (i = 0, k = 0; i < x->f->n_p; i++)
		x->full[i] = i == x->fixed ? x->fixed_value : p[k++];
	diag_fit_state(x->f, x->full, &s);
	return diag_chi2(x->e, x->d, &s, &chi2, NULL, NULL, NULL, r, err);
}

/* Starting rows for the parameters of cause c (offset o in p). */
static int cause_starts(const struct diag_cause *c, const struct diag_data *d,
			double (*rows)[DIAG_PARAMS_MAX], int max)
{
	int n = 1, k, i;

	if (c->start_grid)
		return c->start_grid(d->theta_deg, d->n, rows, max);
	for (k = 0; k < c->n_params; k++)
		n *= c->param[k].n_start > 0 ? c->param[k].n_start : 1;
	n = n < max ? n : max;
	for (i = 0; i < n; i++) {
		int rem = i;

		for (k = 0; k < c->n_params; k++) {
			const struct diag_param *q = &c->param[k];
			int m = q->n_start > 0 ? q->n_start : 1, j = rem % m;

			rem /= m;
			rows[i][k] = m == 1 ? q->nominal :
				q->lo + (q->hi - q->lo) * j / (m - 1);
		}
	}
	return n;
}

static int fit_from(struct diag_eval *e, const struct diag_data *d,
		    struct diag_fit *f, double *p, double *chi2,
		    struct stray_error *err)
{
	struct resid_ctx x = { e, d, f, -1, 0.0, NULL };
	double lo[DIAG_FIT_PMAX], hi[DIAG_FIT_PMAX], full[DIAG_FIT_PMAX];

	x.full = full;
	fit_bounds(f, lo, hi);
	return diag_lm(resid_fn, &x, f->n_p, d->n, p, lo, hi, chi2, err);
}

int diag_fit_run(struct diag_eval *e, const struct diag_data *d,
		 struct diag_fit *f, int warm, struct stray_error *err)
{
	double (*rows)[DIAG_PARAMS_MAX] = malloc(STARTS_MAX * sizeof(*rows));
	const struct diag_cause *last = f->cause[f->n_causes - 1];
	double best_c[KEEP_STARTS], best_p[KEEP_STARTS][DIAG_FIT_PMAX];
	int c, n_rows, i, k, o, rc = STRAY_OK;
	struct diag_state s;

	if (!rows)	/* per call: the step's candidates fit side by side */
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	f->n_p = 0;
	f->k = 0;
	for (c = 0; c < f->n_causes; c++) {
		f->n_p += f->cause[c]->n_params;
		f->k += f->cause[c]->k_bic;
	}
	o = f->n_p - last->n_params;
	if (!warm)	/* every cause from its nominal; the last from its grid */
		for (c = 0, i = 0; c < f->n_causes - 1; c++)
			for (k = 0; k < f->cause[c]->n_params; k++)
				f->p[i++] = f->cause[c]->param[k].nominal;
	n_rows = cause_starts(last, d, rows, STARTS_MAX);
	for (i = 0; i < KEEP_STARTS; i++)
		best_c[i] = INFINITY;
	for (i = 0; i < n_rows && !rc; i++) {	/* screen the starts */
		double p[DIAG_FIT_PMAX], chi2;
		int j;

		memcpy(p, f->p, o * sizeof(*p));
		memcpy(p + o, rows[i], last->n_params * sizeof(*p));
		diag_fit_state(f, p, &s);
		rc = diag_chi2(e, d, &s, &chi2, NULL, NULL, NULL, NULL, err);
		for (j = KEEP_STARTS - 1; !rc && j >= 0 && chi2 < best_c[j]; j--) {
			if (j + 1 < KEEP_STARTS) {
				best_c[j + 1] = best_c[j];
				memcpy(best_p[j + 1], best_p[j], sizeof(best_p[j]));
			}
			best_c[j] = chi2;
			memcpy(best_p[j], p, sizeof(p));
		}
	}
	f->chi2 = INFINITY;
	for (i = 0; i < KEEP_STARTS && !rc && isfinite(best_c[i]); i++) {
		double chi2 = best_c[i];

		if (f->n_p > 0)
			rc = fit_from(e, d, f, best_p[i], &chi2, err);
		if (!rc && chi2 < f->chi2) {
			f->chi2 = chi2;
			memcpy(f->p, best_p[i], sizeof(best_p[i]));
		}
	}
	f->bic = f->chi2 + f->k * log((double)d->n);	/* Schwarz 1978 */
	f->converged = isfinite(f->chi2);
	for (i = 0; i < f->n_p; i++)
		f->ci_lo[i] = f->ci_hi[i] = f->p[i];
	free(rows);
	return rc;
}

/* chi2 with parameter j held at v and the others re-fitted. */
static int profile_at(struct diag_eval *e, const struct diag_data *d,
		      const struct diag_fit *f, int j, double v, double *chi2,
		      struct stray_error *err)
{
	struct resid_ctx x = { e, d, f, j, v, NULL };
	double lo[DIAG_FIT_PMAX], hi[DIAG_FIT_PMAX], full[DIAG_FIT_PMAX];
	double p[DIAG_FIT_PMAX], plo[DIAG_FIT_PMAX], phi[DIAG_FIT_PMAX];
	double *r;
	int i, k, rc;

	x.full = full;
	fit_bounds(f, lo, hi);
	for (i = 0, k = 0; i < f->n_p; i++)
		if (i != j) {
			p[k] = f->p[i];
			plo[k] = lo[i];
			phi[k++] = hi[i];
		}
	if (k > 0)
		return diag_lm(resid_fn, &x, k, d->n, p, plo, phi, chi2, err);
	r = malloc(d->n * sizeof(*r));
	if (!r)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	rc = resid_fn(&x, p, r, err);
	for (i = 0, *chi2 = 0.0; !rc && i < (int)d->n; i++)
		*chi2 += r[i] * r[i];
	free(r);
	return rc;
}

/* One side of the interval: bisect for chi2_min + delta toward bound. */
static int profile_edge(struct diag_eval *e, const struct diag_data *d,
			const struct diag_fit *f, int j, double bound,
			double target, double *edge, struct stray_error *err)
{
	double in = f->p[j], out = bound, chi2;
	int it, rc;

	*edge = bound;
	if (bound == in)
		return STRAY_OK;
	rc = profile_at(e, d, f, j, bound, &chi2, err);
	if (rc || chi2 < target)
		return rc;	/* the bound is inside: the interval reaches it */
	for (it = 0; it < PROFILE_STEPS; it++) {
		double mid = 0.5 * (in + out);

		rc = profile_at(e, d, f, j, mid, &chi2, err);
		if (rc)
			return rc;
		if (chi2 < target)
			in = mid;
		else
			out = mid;
	}
	*edge = 0.5 * (in + out);
	return STRAY_OK;
}

int diag_fit_intervals(struct diag_eval *e, const struct diag_data *d,
		       struct diag_fit *f, struct stray_error *err)
{
	double lo[DIAG_FIT_PMAX], hi[DIAG_FIT_PMAX], delta;
	int j, dof = (int)d->n - f->k, rc = STRAY_OK;

	fit_bounds(f, lo, hi);
	delta = DIAG_CI_DCHI2 * (dof > 0 ? fmax(1.0, f->chi2 / dof) : 1.0);
	for (j = 0; j < f->n_p && !rc; j++) {
		rc = profile_edge(e, d, f, j, lo[j], f->chi2 + delta,
				  &f->ci_lo[j], err);
		if (!rc)
			rc = profile_edge(e, d, f, j, hi[j], f->chi2 + delta,
					  &f->ci_hi[j], err);
	}
	return rc;
}

/* Wilson-Hilferty (1931): (chi2/dof)^(1/3) is near normal; good to a few
 * per cent in p at the 0.01 level for dof >= 3, plenty for a decision. */
double diag_chi2_pvalue(double chi2, int dof)
{
	double k = dof > 0 ? dof : 1, v = 2.0 / (9.0 * k);
	double z = (cbrt(chi2 / k) - (1.0 - v)) / sqrt(v);

	return 0.5 * erfc(z / M_SQRT2);
}
