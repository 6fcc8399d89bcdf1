/*
 * surfaces_fit.c - the re-weighting fit of the surface at fault
 * (surfaces.c has the method and the table): a factor per candidate
 * group fitted to the log10 residuals, groups entering by BIC (greedy
 * forward selection), intervals by profile chi2.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "diagnose/diag_fit.h"
#include "diagnose/diag_result.h"
#include "diagnose/diag_surfaces.h"
#include "path_rows.h"
#include "surfaces.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/integrator.h"
#include "tracer/obj_export.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

struct sfit {
	const struct diag_surf_table *t;
	const struct diag_data *d;
	size_t *jm;		/* measured point -> traced angle */
	size_t n_fit;		/* points with theta != 0 */
	size_t *pt;		/* fitted point -> measured index */
	double *p, *var;	/* per traced angle */
	int n_free, free_c[DIAG_SURF_NAMED_MAX];	/* groups fitted */
	double f[DIAG_SURF_MAX];	/* current factors, 1 = scene */
	const double *base;	/* per measured point, the registry's model
				 * over the nominal (NULL: 1) */
	int fixed_k;		/* profile: this free index fixed, -1 none */
	double fixed_x;
	size_t evals;
};

static void reweight(struct sfit *x)
{
	const struct diag_surf_table *t = x->t;
	size_t i;
	int k;

	memset(x->p, 0, t->n_theta * sizeof(*x->p));
	memset(x->var, 0, t->n_theta * sizeof(*x->var));
	for (i = 0; i < t->n_rows; i++) {
		double w = 1.0;

		for (k = 0; k < t->n_c[i]; k++)
			w *= x->f[t->c[i][k]];
		x->p[t->j[i]] += t->v[i] * w;
		x->var[t->j[i]] += t->var[i] * w * w;
	}
	x->evals++;
}

/* Whitened log10 residuals at the current factors. */
static void residuals(struct sfit *x, double *r)
{
	const struct diag_data *d = x->d;
	double p0 = x->p[0], v0 = p0 > 0.0 ? x->var[0] / (p0 * p0) : 0.0;
	size_t m;

	for (m = 0; m < x->n_fit; m++) {
		size_t i = x->pt[m], j = x->jm[i];
		double a = p0 > 0.0 ? x->p[j] / p0 : 0.0, rm, rs, s;

		a *= x->base ? x->base[i] : 1.0;
		a = a > 1e-30 ? a : 1e-30;
		rm = d->sigma[i] / d->alpha[i];
		rs = x->p[j] > 0.0 ? x->var[j] / (x->p[j] * x->p[j]) + v0 : 0.0;
		s = sqrt(rm * rm + rs) / M_LN10;
		r[m] = log10(d->alpha[i] / a) / s;
	}
}

static int resid_fn(void *user, const double *p, double *r,
		    struct stray_error *err)
{
	struct sfit *x = user;
	int k, q = 0;

	(void)err;
	for (k = 0; k < x->n_free; k++)
		x->f[x->free_c[k]] = pow(10.0, k == x->fixed_k ? x->fixed_x :
					 p[q++]);
	reweight(x);
	residuals(x, r);
	return STRAY_OK;
}

static double hi_bound(const struct diag_surf_table *t, int c)
{
	/* a Lambertian group cannot reflect more than all */
	double h = t->abg[c] || !(t->rho[c] > 0.0) ? DIAG_SURF_LOG_BOUND :
		fmin(DIAG_SURF_LOG_BOUND, log10(1.0 / t->rho[c]));

	return h;
}

/* Fit the free groups' log10 factors (p in/out, all free ones, the
 * fixed one, if any, held at fixed_x); chi2 out. */
static int fit_free(struct sfit *x, double *p, double *chi2, double *r,
		    struct stray_error *err)
{
	double q[DIAG_SURF_NAMED_MAX], lo[DIAG_SURF_NAMED_MAX],
	       hi[DIAG_SURF_NAMED_MAX];
	int k, n = 0, rc;

	for (k = 0; k < x->n_free; k++) {
		if (k == x->fixed_k)
			continue;
		q[n] = p[k];
		lo[n] = -DIAG_SURF_LOG_BOUND;
		hi[n] = hi_bound(x->t, x->free_c[k]);
		n++;
	}
	if (n == 0) {
		resid_fn(x, q, r, err);
		for (*chi2 = 0.0, k = 0; k < (int)x->n_fit; k++)
			*chi2 += r[k] * r[k];
		return STRAY_OK;
	}
	rc = diag_lm(resid_fn, x, n, x->n_fit, q, lo, hi, chi2, err);
	for (n = 0, k = 0; k < x->n_free; k++)
		if (k != x->fixed_k)
			p[k] = q[n++];
	return rc;
}

/* Profile-chi2 edge of free parameter k from best toward bound. */
static int profile_edge(struct sfit *x, const double *best, int k,
			double chi2_min, double target, double bound,
			double *edge, double *r, struct stray_error *err)
{
	double p[DIAG_SURF_NAMED_MAX], in = best[k], out = bound, c;
	double step = bound > best[k] ? 0.02 : -0.02;
	int i, rc = STRAY_OK;

	x->fixed_k = k;
	memcpy(p, best, sizeof(p));
	/* walk out until chi2 exceeds the target, then bisect */
	for (x->fixed_x = best[k] + step;
	     (step > 0 ? x->fixed_x < bound : x->fixed_x > bound) && !rc;
	     x->fixed_x += step, step *= 1.6) {
		rc = fit_free(x, p, &c, r, err);
		if (c - chi2_min >= target) {
			out = x->fixed_x;
			break;
		}
		in = x->fixed_x;
	}
	if (step > 0 ? x->fixed_x >= bound : x->fixed_x <= bound)
		out = bound;
	for (i = 0; i < 30 && !rc && fabs(out - in) > 1e-4; i++) {
		x->fixed_x = 0.5 * (in + out);
		memcpy(p, best, sizeof(p));
		rc = fit_free(x, p, &c, r, err);
		if (c - chi2_min >= target)
			out = x->fixed_x;
		else
			in = x->fixed_x;
	}
	x->fixed_k = -1;
	*edge = 0.5 * (in + out);
	return rc;
}

static double rms_of(const struct sfit *x, const double *r)
{
	/* rms of the plain log10 residuals (not whitened) */
	const struct diag_data *d = x->d;
	double p0 = x->p[0], s = 0.0;
	size_t m;

	(void)r;
	for (m = 0; m < x->n_fit; m++) {
		size_t i = x->pt[m];
		double a = (p0 > 0.0 ? x->p[x->jm[i]] / p0 : 0.0) *
			   (x->base ? x->base[i] : 1.0);
		double l = log10(d->alpha[i] / (a > 1e-30 ? a : 1e-30));

		s += l * l;
	}
	return x->n_fit ? sqrt(s / x->n_fit) : 0.0;
}

int diag_surfaces_fit(const struct diag_surf_table *t,
		      const struct diag_data *d, struct diag_surfaces *s,
		      struct stray_error *err)
{
	return diag_surfaces_fit_on(t, d, NULL, s, err);
}

int diag_surfaces_fit_on(const struct diag_surf_table *t,
			 const struct diag_data *d, const double *base,
			 struct diag_surfaces *s, struct stray_error *err)
{
	struct sfit x;
	double *r, best[DIAG_SURF_NAMED_MAX] = { 0 }, chi2, ln_n;
	struct timespec t0, t1;
	size_t i;
	int k, c, rc = STRAY_OK;

	clock_gettime(CLOCK_MONOTONIC, &t0);
	memset(s, 0, sizeof(*s));
	memset(&x, 0, sizeof(x));
	s->chi2_retrace = s->rms_retrace = NAN;
	s->n_cand = t->n_cand;
	s->n_rows = t->n_rows;
	for (c = 0; c < t->n_cand; c++) {
		snprintf(s->name[c], sizeof(s->name[c]), "%s", t->name[c]);
		s->group[c] = t->group[c];
		s->abg[c] = t->abg[c];
		s->rho[c] = t->rho[c];
	}
	x.t = t;
	x.d = d;
	x.base = base;
	s->base = base;
	x.fixed_k = -1;
	x.jm = malloc(d->n * sizeof(*x.jm));
	x.pt = malloc(d->n * sizeof(*x.pt));
	x.p = malloc(2 * t->n_theta * sizeof(*x.p));
	r = malloc((d->n + 1) * sizeof(*r));
	if (!x.jm || !x.pt || !x.p || !r) {
		rc = stray_error_set(err, STRAY_ENOMEM, "diagnose",
				     "out of memory");
		goto out;
	}
	x.var = x.p + t->n_theta;
	for (c = 0; c < DIAG_SURF_MAX; c++)
		x.f[c] = 1.0;
	for (i = 0; i < d->n; i++) {
		x.jm[i] = diag_surf_find_theta(t, d->theta_deg[i]);
		if (d->theta_deg[i] != 0.0)
			x.pt[x.n_fit++] = i;
	}
	s->n_fit = (int)x.n_fit;
	ln_n = log((double)(x.n_fit > 1 ? x.n_fit : 2));
	fit_free(&x, best, &chi2, r, err);
	s->chi2_before = s->chi2_after = chi2;
	s->bic_before = s->bic_after = chi2;
	s->rms_before = s->rms_after = rms_of(&x, r);
	/* greedy forward selection: the group whose factor, fitted with the
	 * ones already in, lowers BIC the most, while by > the margin */
	while (!rc && x.n_free < DIAG_SURF_NAMED_MAX) {
		double bc = INFINITY, bp[DIAG_SURF_NAMED_MAX];
		int bcand = -1;

		for (c = 0; c < t->n_cand && !rc; c++) {
			double p[DIAG_SURF_NAMED_MAX], c2;
			int in = 0;

			for (k = 0; k < x.n_free; k++)
				in |= x.free_c[k] == c;
			if (in)
				continue;
			memcpy(p, best, sizeof(p));
			p[x.n_free] = 0.0;
			x.free_c[x.n_free++] = c;
			rc = fit_free(&x, p, &c2, r, err);
			x.f[c] = 1.0;
			x.n_free--;
			if (!rc && c2 < bc) {
				bc = c2;
				bcand = c;
				memcpy(bp, p, sizeof(bp));
			}
		}
		if (rc || bcand < 0 || bc + (x.n_free + 1) * ln_n >
		    s->bic_after - DIAG_BIC_MARGIN)
			break;
		x.free_c[x.n_free++] = bcand;
		memcpy(best, bp, sizeof(best));
		s->chi2_after = bc;
		s->bic_after = bc + x.n_free * ln_n;
	}
	/* the final fit and its rms */
	if (!rc)
		rc = fit_free(&x, best, &chi2, r, err);
	if (!rc && x.n_free > 0) {
		int dof = (int)x.n_fit - x.n_free;
		double red = dof > 0 ? chi2 / dof : 1.0;
		double target = DIAG_CI_DCHI2 * (red > 1.0 ? red : 1.0);

		s->chi2_after = chi2;
		s->rms_after = rms_of(&x, r);
		s->n_named = x.n_free;
		for (k = 0; k < x.n_free && !rc; k++) {
			s->named[k] = x.free_c[k];
			s->log10_f[k] = best[k];
			rc = profile_edge(&x, best, k, chi2, target,
					  -DIAG_SURF_LOG_BOUND, &s->ci_lo[k],
					  r, err);
			if (!rc)
				rc = profile_edge(&x, best, k, chi2, target,
						  hi_bound(t, x.free_c[k]),
						  &s->ci_hi[k], r, err);
		}
	}
out:
	s->n_evals = x.evals;
	clock_gettime(CLOCK_MONOTONIC, &t1);
	s->fit_seconds = (double)(t1.tv_sec - t0.tv_sec) +
			 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
	free(x.jm);
	free(x.pt);
	free(x.p);
	free(r);
	return rc;
}
