/*
 * geometry_blend.c - the model at a state's geometry: the traced nodes
 * around it on each active axis (their corners), blended multilinearly in
 * log alpha at the state's coating (thesis §4 re-weighting of each
 * corner's path table); with e->factorized, the interaction of some axes
 * with the others neglected (run.c's screen).  The last blend is kept:
 * a fit of the leak, the floor, the offset or the beam varies none of
 * what it depends on (evaluate.c post-processes it), so it is computed
 * once for all their starting points.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "trace_cache.h"
#include "stray/errfmt.h"

/* A node value as a cache key: the scene's own value is NaN, so the
 * nominal node shares the nominal trace. */
static double node_key(const struct diag_cause *c, double v)
{
	if (c && c->n_params > 0 && v == c->param[0].nominal)
		return NAN;
	return v;
}

struct corners {
	int n_axis, axis[DIAG_GEO_N];
	double lo[DIAG_GEO_N], hi[DIAG_GEO_N], t[DIAG_GEO_N];
};

static void bracket(const struct diag_eval *e, const struct diag_state *s,
		    struct corners *c)
{
	int a, k;

	c->n_axis = 0;
	for (a = 0; a < DIAG_GEO_N; a++) {
		const struct diag_cause *cs = diag_eval_axis_cause(e, a);
		double v = s->geo[a];
		int m = c->n_axis;

		if (isnan(v) || isnan(node_key(cs, v)))
			continue;
		c->axis[m] = a;
		c->lo[m] = c->hi[m] = v;
		c->t[m] = 0.0;
		if (cs && cs->n_nodes > 1) {
			v = fmin(fmax(v, cs->nodes[0]),
				 cs->nodes[cs->n_nodes - 1]);
			for (k = 0; k + 2 < cs->n_nodes &&
			     v > cs->nodes[k + 1]; k++)
				;
			c->lo[m] = node_key(cs, cs->nodes[k]);
			c->hi[m] = node_key(cs, cs->nodes[k + 1]);
			c->t[m] = (v - cs->nodes[k]) /
				(cs->nodes[k + 1] - cs->nodes[k]);
		}
		c->n_axis++;
	}
}

/* alpha and relative variance at the centre of each measured angle (and
 * at the fine sub-points when t is fine), for one trace. */
void diag_trace_alpha(const struct diag_eval *e, const struct diag_trace *t,
		      double rho, double slope, double *p, double *var,
		      double *alpha, double *relvar, int all_sub)
{
	size_t i;
	int k;
	double p0, v0;

	if (slope != 0.0)	/* cause_spectral_slope.c */
		diag_trace_power_band(t, rho, slope, p, var);
	else
		diag_trace_power(t, rho, p, var);
	p0 = p[t->ref];
	v0 = p0 > 0.0 ? var[t->ref] / (p0 * p0) : 0.0;
	for (i = 0; i < e->n; i++)
		for (k = 0; k < DIAG_SUB; k++) {
			size_t j, o = i * DIAG_SUB + k;

			if (!all_sub && k != DIAG_SUB / 2)
				continue;
			j = t->idx[o];
			alpha[o] = p0 > 0.0 ? p[j] / p0 : 0.0;
			relvar[o] = p[j] > 0.0 ?
				var[j] / (p[j] * p[j]) + v0 : 0.0;
		}
}

/* Blend the corners of the active axes in `use` (a bit per axis of c;
 * the others at the scene's own value): log alpha multilinear (linear in
 * alpha where a corner is 0), relative sigma likewise. */
static int blend_axes(struct diag_eval *e, const struct diag_state *s,
		      const struct corners *c, unsigned use, double *work,
		      double *alpha, double *relcov, struct stray_error *err)
{
	size_t i, nt, nm = e->n * DIAG_SUB;
	double *p, *var, *a_c, *rv_c, *la, *lin;
	int corner, n_corner, rc = STRAY_OK;

	n_corner = 1 << c->n_axis;
	nt = e->n * DIAG_SUB + 1;	/* bounds every trace's angle count */
	p = work;
	var = p + nt;
	a_c = var + nt;
	rv_c = a_c + nm;
	la = rv_c + nm;
	lin = la + e->n;
	memset(la, 0, 2 * e->n * sizeof(*la));
	memset(relcov, 0, e->n * e->n * sizeof(*relcov));
	for (i = 0; i < e->n; i++)
		alpha[i] = 1.0;	/* 1: every corner positive so far */
	for (corner = 0; corner < n_corner && !rc; corner++) {
		double geo[DIAG_GEO_N], w = 1.0;
		const struct diag_trace *t;
		int a;

		if (corner & ~use)
			continue;
		for (a = 0; a < DIAG_GEO_N; a++)
			geo[a] = NAN;
		for (a = 0; a < c->n_axis; a++) {
			int up = (corner >> a) & 1;

			if (!((use >> a) & 1))
				continue;
			geo[c->axis[a]] = up ? c->hi[a] : c->lo[a];
			w *= up ? c->t[a] : 1.0 - c->t[a];
		}
		if (w == 0.0)
			continue;
		rc = diag_trace_get(e, geo, 0, &t, err);
		if (rc)
			break;
		diag_trace_alpha(e, t, s->reflectance, s->spectral_slope, p, var, a_c,
			    rv_c, 0);
		for (i = 0; i < e->n; i++) {
			double ai = a_c[i * DIAG_SUB + DIAG_SUB / 2];

			lin[i] += w * ai;
			if (ai > 0.0)
				la[i] += w * log(ai);
			else
				alpha[i] = 0.0;
		}
		for (i = 0; i < e->n * e->n; i++)
			relcov[i] += w * t->relcov[i];
	}
	for (i = 0; i < e->n; i++)
		alpha[i] = alpha[i] > 0.0 ? exp(la[i]) : lin[i];
	return rc;
}

/*
 * The interaction neglected (run.c's screen of a re-trace cause joining
 * others, e->factorized): the factorized axes' effect taken from their
 * own nodes at the scene's other values, alpha = alpha(rest) x
 * alpha(factorized) / alpha(nominal), so no trace of the combined grid
 * is needed; the two blends' relative covariances add (their traces are
 * not all one guide's: more noise, a screen that lets more through).
 */
static int blend_factorized(struct diag_eval *e, const struct diag_state *s,
			    const struct corners *c, unsigned fac,
			    double *work, double *alpha, double *relcov,
			    struct stray_error *err)
{
	size_t i, n = e->n;
	unsigned all = (1u << c->n_axis) - 1u;
	double *buf = malloc((2 * n + 2 * n * n) * sizeof(*buf));
	double *a_f, *a_0, *rc_f, *rc_0;
	int rc;

	if (!buf)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	a_f = buf;
	a_0 = a_f + n;
	rc_f = a_0 + n;
	rc_0 = rc_f + n * n;
	rc = blend_axes(e, s, c, all & ~fac, work, alpha, relcov, err);
	if (!rc)
		rc = blend_axes(e, s, c, fac, work, a_f, rc_f, err);
	if (!rc)	/* no axis: the nominal geometry */
		rc = blend_axes(e, s, c, 0u, work, a_0, rc_0, err);
	for (i = 0; !rc && i < n; i++)
		alpha[i] = a_0[i] > 0.0 ? alpha[i] * a_f[i] / a_0[i] :
			   alpha[i];
	for (i = 0; !rc && i < n * n; i++)
		relcov[i] += rc_f[i];
	free(buf);
	return rc;
}

static int blend_geometry(struct diag_eval *e, const struct diag_state *s,
			  double *work, double *alpha, double *relcov,
			  struct stray_error *err)
{
	struct corners c;
	unsigned fac = 0u, all;
	int m;

	bracket(e, s, &c);
	all = (1u << c.n_axis) - 1u;
	for (m = 0; m < c.n_axis; m++)
		if ((e->factorized >> c.axis[m]) & 1u)
			fac |= 1u << m;
	if (fac && fac != all)	/* a combined grid: not traced */
		return blend_factorized(e, s, &c, fac, work, alpha, relcov,
					err);
	return blend_axes(e, s, &c, all, work, alpha, relcov, err);
}

/* What a blend depends on: the geometry, the coating, the factorized
 * axes (compared bit for bit: a miss only recomputes). */
static void blend_key(const struct diag_eval *e, const struct diag_state *s,
		      double *key)
{
	memcpy(key, s->geo, sizeof(s->geo));
	key[DIAG_GEO_N] = s->reflectance;
	key[DIAG_GEO_N + 1] = s->spectral_slope;
	key[DIAG_GEO_N + 2] = (double)e->factorized;
}

int diag_blend_geometry(struct diag_eval *e, const struct diag_state *s,
			double *work, double *alpha, double *relcov,
			struct stray_error *err)
{
	double key[DIAG_BLEND_KEY];
	size_t n = e->n;
	int rc;

	blend_key(e, s, key);
	if (e->blend_alpha && memcmp(key, e->blend_key, sizeof(key)) == 0) {
		memcpy(alpha, e->blend_alpha, n * sizeof(*alpha));
		memcpy(relcov, e->blend_alpha + n, n * n * sizeof(*relcov));
		return STRAY_OK;
	}
	rc = blend_geometry(e, s, work, alpha, relcov, err);
	if (rc)
		return rc;
	if (!e->blend_alpha)	/* no room: computed every time */
		e->blend_alpha = malloc((n + n * n) * sizeof(*alpha));
	if (e->blend_alpha) {
		memcpy(e->blend_key, key, sizeof(key));
		memcpy(e->blend_alpha, alpha, n * sizeof(*alpha));
		memcpy(e->blend_alpha + n, relcov, n * n * sizeof(*relcov));
	}
	return STRAY_OK;
}
