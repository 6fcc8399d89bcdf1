/*
 * evaluate.c - a model state to alpha(theta_i) with its sigma.
 *
 * Geometry (re-trace causes) is interpolated multilinearly in log alpha
 * between traced nodes of each active axis; the interior reflectance is
 * applied to each node by re-weighting its path table; the angle offset,
 * the floor, the leak and the scale post-process the curve.
 * Approximation (stated in the report): the angle offset's correction
 * alpha(theta + d) / alpha(theta) is taken from the nominal geometry's
 * fine grid (at the state's reflectance), not from each geometry node;
 * that trace has a quarter of the paths, as only ratios within it are
 * used (common random numbers: most of its noise cancels in them).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "trace_cache.h"
#include "tracer/scene_file.h"
#include "stray/errfmt.h"
#include "lens.h"

#define LEAK_EDGE_DEG 0.2	/* soft window edge, so the fit has a slope */
#define BEAM_RINGS 8		/* the beam disk's quadrature */
#define BEAM_AZ 16

void diag_eval_init(struct diag_eval *e, const char *scene,
		    const double *theta_deg, size_t n,
		    const struct tracer_runner *runner)
{
	memset(e, 0, sizeof(*e));
	e->scene = scene;
	e->runner = runner;
	/* the vane family: built-in ref4 or a "type": "vanes" file */
	e->parametric = strcmp(scene, "ref4") == 0 ||
			tracer_scene_file_is_vanes(scene);
	e->n_paths = 200000;
	e->seed = 1;
	e->threads = 1;
	e->theta_deg = theta_deg;
	e->n = n;
	e->sub_step_deg = DIAG_OFFSET_MAX_DEG / (DIAG_SUB / 2);
}

int diag_eval_prepare(struct diag_eval *e, struct stray_error *err)
{
	double nominal[DIAG_GEO_N];
	const struct diag_trace *t;
	size_t i;
	int rc, a;

	for (a = 0; a < DIAG_GEO_N; a++)
		nominal[a] = NAN;
	rc = diag_trace_get(e, nominal, 0, &t, err);
	if (!rc)	/* the registry fitted to the scene */
		rc = diag_eval_causes(e, t->base_rho, err);
	if (rc)
		return rc;
	e->direct_share = malloc((e->n ? e->n : 1) * sizeof(double));
	if (!e->direct_share)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	for (i = 0; i < e->n; i++)
		e->direct_share[i] = t->direct[t->idx[i * DIAG_SUB +
						       DIAG_SUB / 2]];
	if (e->lens) {	/* system curves: diagnose/lens.c */
		struct diag_state s0;
		double *a0 = malloc(2 * (e->n ? e->n : 1) * sizeof(double));

		if (!a0)
			return stray_error_set(err, STRAY_ENOMEM, "diagnose",
					       "out of memory");
		diag_state_nominal(&s0);
		rc = diag_eval_model(e, &s0, a0, a0 + e->n, NULL, err);
		if (!rc)
			rc = diag_lens_prepare(e, a0, err);
		free(a0);
	}
	return rc;
}

void diag_eval_free(struct diag_eval *e)
{
	diag_trace_cache_free(e);
	free(e->direct_share);
	e->direct_share = NULL;
	free(e->blend_alpha);	/* geometry_blend.c's last blend */
	e->blend_alpha = NULL;
	free(e->chol_in);	/* fit.c's factor of the last covariance */
	e->chol_in = e->chol_out = NULL;
	e->chol_n = 0;
	diag_lens_free(e);
}

/* alpha(theta_i + d) / alpha(theta_i) on the nominal fine grid, by
 * quadratic interpolation of log alpha through the nearest 3 points. */
static int offset_factor(struct diag_eval *e, const struct diag_state *s,
			 double *work, double *factor,
			 struct stray_error *err)
{
	double nominal[DIAG_GEO_N];
	const struct diag_trace *t;
	size_t i, nm = e->n * DIAG_SUB;
	double *p, *var, *a, *rv, d = s->angle_offset_deg, h = e->sub_step_deg;
	int rc, g;

	for (g = 0; g < DIAG_GEO_N; g++)
		nominal[g] = NAN;
	rc = diag_trace_get(e, nominal, 1, &t, err);

	if (rc)
		return rc;
	p = work;
	var = p + t->n_theta;
	a = var + t->n_theta;
	rv = a + nm;
	diag_trace_alpha(e, t, s->reflectance, s->spectral_slope, p, var, a, rv,
		    1);
	for (i = 0; i < e->n; i++) {
		double x = fmin(fmax(d / h, -(DIAG_SUB / 2)), DIAG_SUB / 2);
		int m = (int)lround(x), k;
		const double *y;
		double c = a[i * DIAG_SUB + DIAG_SUB / 2], u;

		m = m < -(DIAG_SUB / 2 - 1) ? -(DIAG_SUB / 2 - 1) :
		    m > DIAG_SUB / 2 - 1 ? DIAG_SUB / 2 - 1 : m;
		y = &a[i * DIAG_SUB + DIAG_SUB / 2 + m - 1];
		u = x - m;	/* in [-1, 1] around the middle point */
		factor[i] = 1.0;
		for (k = 0; k < 3 && y[k] > 0.0; k++)
			;
		if (k == 3 && c > 0.0)	/* quadratic in log alpha */
			factor[i] = exp(0.5 * u * (u - 1.0) * log(y[0]) +
					(1.0 - u * u) * log(y[1]) +
					0.5 * u * (u + 1.0) * log(y[2])) / c;
		else if (c > 0.0)
			factor[i] = (0.5 * u * (u - 1.0) * y[0] +
				     (1.0 - u * u) * y[1] +
				     0.5 * u * (u + 1.0) * y[2]) / c;
	}
	return STRAY_OK;
}

/* The nominal fine grid sorted by angle: alpha and its log (taken once
 * per state where alpha > 0: the same values every call would take). */
struct fine_curve {
	const double *th, *a, *la;
	size_t m;
	size_t hint;	/* the last point found (fine_find) */
};

/*
 * lo with th[lo] <= phi < th[lo + 1], for th[0] < phi < th[m - 1] and th
 * strictly increasing: the one interval a binary search finds, searched
 * outward from the last one (a beam average asks for points close
 * together: a few steps, not a search of every point per call).
 */
static size_t fine_find(struct fine_curve *f, double phi)
{
	const double *th = f->th;
	size_t lo = f->hint < f->m - 1 ? f->hint : 0, hi, step = 1;

	if (th[lo] <= phi) {		/* gallop up; th[m - 1] > phi */
		hi = lo + 1;
		while (th[hi] <= phi) {
			lo = hi;
			hi = lo + step < f->m - 1 ? lo + step : f->m - 1;
			step *= 2;
		}
	} else {			/* gallop down; th[0] < phi */
		do {
			hi = lo;
			lo = lo > step ? lo - step : 0;
			step *= 2;
		} while (th[lo] > phi);
	}
	while (hi - lo > 1) {
		size_t mid = (lo + hi) / 2;

		if (th[mid] <= phi)
			lo = mid;
		else
			hi = mid;
	}
	f->hint = lo;
	return lo;
}

/* alpha at off-axis angle phi, log-linear between the fine points
 * (sorted by angle), held constant beyond them. */
static double fine_at(struct fine_curve *f, double phi)
{
	const double *th = f->th, *a = f->a, *la = f->la;
	size_t m = f->m, lo, hi;

	if (phi <= th[0])
		return a[0];
	if (phi >= th[m - 1])
		return a[m - 1];
	lo = fine_find(f, phi);
	hi = lo + 1;
	/* quadratic in log alpha through lo, hi and the nearer outer
	 * neighbour (Lagrange), where all three are positive */
	{
		size_t c = lo == 0 ? 0 : hi == m - 1 ? lo - 1 :
			   phi - th[lo] < th[hi] - phi ? lo - 1 : lo;

		if (m >= 3 && a[c] > 0.0 && a[c + 1] > 0.0 && a[c + 2] > 0.0) {
			double x0 = th[c], x1 = th[c + 1], x2 = th[c + 2];

			return exp(la[c] * (phi - x1) * (phi - x2) /
				   ((x0 - x1) * (x0 - x2)) +
				   la[c + 1] * (phi - x0) * (phi - x2) /
				   ((x1 - x0) * (x1 - x2)) +
				   la[c + 2] * (phi - x0) * (phi - x1) /
				   ((x2 - x0) * (x2 - x1)));
		}
	}
	if (a[lo] > 0.0 && a[hi] > 0.0)
		return exp(la[lo] + (la[hi] - la[lo]) *
			   (phi - th[lo]) / (th[hi] - th[lo]));
	return a[lo] + (a[hi] - a[lo]) * (phi - th[lo]) / (th[hi] - th[lo]);
}

/* The beam disk's quadrature (polar midpoint rule): ring radii, their
 * weights r exp(-2 r^2 / g^2) (g > 0), the azimuths' cos and sin; the
 * same for every angle of a state, so computed once per state. */
struct beam_quad {
	double r[BEAM_RINGS], w[BEAM_RINGS], c[BEAM_AZ], s[BEAM_AZ];
};

static void beam_quad_init(struct beam_quad *q, double b, double g)
{
	int ir, ia;

	for (ir = 0; ir < BEAM_RINGS; ir++) {
		q->r[ir] = b * (ir + 0.5) / BEAM_RINGS;
		q->w[ir] = q->r[ir];
		if (g > 0.0)
			q->w[ir] *= exp(-2.0 * q->r[ir] * q->r[ir] / (g * g));
	}
	for (ia = 0; ia < BEAM_AZ; ia++) {
		double ph = 2.0 * M_PI * (ia + 0.5) / BEAM_AZ;

		q->c[ia] = cos(ph);
		q->s[ia] = sin(ph);
	}
}

/* The beam average of alpha about theta: directions (theta + u, v) over
 * the disk |(u, v)| <= b, weighted exp(-2 r^2 / g^2) when g > 0 (polar
 * midpoint rule); an axisymmetric baffle sees off-axis angle
 * sqrt((theta + u)^2 + v^2) (small angles). */
static double beam_mean(struct fine_curve *f, double theta,
			const struct beam_quad *q)
{
	double sum = 0.0, sw = 0.0;
	int ir, ia;

	for (ir = 0; ir < BEAM_RINGS; ir++) {
		double r = q->r[ir], w = q->w[ir];

		for (ia = 0; ia < BEAM_AZ; ia++) {
			double u = theta + r * q->c[ia], v = r * q->s[ia];

			sum += w * fine_at(f, sqrt(u * u + v * v));
			sw += w;
		}
	}
	return sw > 0.0 ? sum / sw : fine_at(f, theta);
}

static int cmp_pair(const void *x, const void *y)
{
	const double *p = x, *q = y;

	return (p[0] > q[0]) - (p[0] < q[0]);
}

/*
 * The lab beam (cause_beam_divergence.c, cause_beam_profile.c): the
 * measured P(theta) / P(0) is the beam average of the model about both
 * angles.  The average runs over the nominal fine grid (every measured
 * angle +- 1 deg, log-linear between windows: the measured angles should
 * be <= 2 deg apart where the curve is steep), at the state's coating;
 * factor = (<alpha>(theta_i) / alpha(theta_i)) / <alpha>(0).
 */
static int beam_factor(struct diag_eval *e, const struct diag_state *s,
		       double *factor, struct stray_error *err)
{
	double nominal[DIAG_GEO_N], b = s->beam_half_deg, h = e->sub_step_deg;
	const struct diag_trace *t;
	struct beam_quad q;
	struct fine_curve f;
	size_t i, m = 0, nm = e->n * DIAG_SUB, nt;
	double *buf, *p, *var, *a, *rv, *pair, *th, *al, *la, a0;
	int rc, g, k;

	for (g = 0; g < DIAG_GEO_N; g++)
		nominal[g] = NAN;
	rc = diag_trace_get(e, nominal, 1, &t, err);
	if (rc)
		return rc;
	nt = t->n_theta;
	buf = malloc((2 * nt + 7 * nm + 1) * sizeof(*buf));
	if (!buf)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	p = buf;
	var = p + nt;
	a = var + nt;
	rv = a + nm;
	pair = rv + nm;
	th = pair + 2 * nm;
	al = th + nm;
	la = al + nm;
	diag_trace_alpha(e, t, s->reflectance, s->spectral_slope, p, var, a, rv,
		    1);
	for (i = 0; i < e->n; i++)
		for (k = 0; k < DIAG_SUB; k++) {
			pair[2 * m] = fabs(e->theta_deg[i] +
					   (k - DIAG_SUB / 2) * h);
			pair[2 * m + 1] = a[i * DIAG_SUB + k];
			m++;
		}
	qsort(pair, m, 2 * sizeof(*pair), cmp_pair);
	for (i = 0, k = 0; i < m; i++) {	/* one point per angle */
		if (k > 0 && pair[2 * i] - th[k - 1] < 1e-9)
			continue;
		th[k] = pair[2 * i];
		al[k] = pair[2 * i + 1];
		la[k] = al[k] > 0.0 ? log(al[k]) : 0.0;	/* read if > 0 */
		k++;
	}
	f.th = th;
	f.a = al;
	f.la = la;
	f.m = (size_t)k;
	f.hint = 0;
	beam_quad_init(&q, b, s->beam_gauss_deg);
	a0 = th[0] <= 1.0 ? beam_mean(&f, 0.0, &q) / fine_at(&f, 0.0) : 1.0;
	for (i = 0; i < e->n; i++) {
		double c = a[i * DIAG_SUB + DIAG_SUB / 2];

		factor[i] = c > 0.0 && a0 > 0.0 ?
			beam_mean(&f, e->theta_deg[i], &q) / c / a0 :
			1.0;
	}
	free(buf);
	return STRAY_OK;
}

static double window(double theta, double lo, double hi)
{
	return 1.0 / (1.0 + exp(-(theta - lo) / LEAK_EDGE_DEG)) /
	       (1.0 + exp(-(hi - theta) / LEAK_EDGE_DEG));
}

int diag_eval_model(struct diag_eval *e, const struct diag_state *s,
		    double *alpha, double *sigma, double *relcov,
		    struct stray_error *err)
{
	size_t i, k, n = e->n, nt = n * DIAG_SUB + 1, n_work;
	double *work, *rc_own = NULL, *factor, *frac, *bfac;
	int rc;

	n_work = 2 * nt + 2 * n * DIAG_SUB + 5 * n;
	work = malloc(n_work * sizeof(*work));
	if (!relcov)
		relcov = rc_own = malloc(n * n * sizeof(*relcov));
	if (!work || !relcov) {
		free(work);
		free(rc_own);
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	}
	factor = work + n_work - 3 * n;
	frac = factor + n;
	bfac = frac + n;
	rc = diag_blend_geometry(e, s, work, alpha, relcov, err);
	if (!rc && s->angle_offset_deg != 0.0)
		rc = offset_factor(e, s, work, factor, err);
	if (!rc && s->beam_half_deg > 0.0)
		rc = beam_factor(e, s, bfac, err);
	for (i = 0; !rc && i < n; i++) {
		double th = e->theta_deg[i], a = alpha[i], g;

		if (s->angle_offset_deg != 0.0)
			a *= factor[i];
		if (s->beam_half_deg > 0.0)
			a *= bfac[i];
		a = diag_lens_apply(e, s, i, a);	/* cause_lens_*.c */
		a *= pow(10.0, s->scale_log10);	/* cause_scale.c */
		g = a;		/* the traced part carries the MC error */
		a += s->floor;
		if (isfinite(s->leak_log10))
			a += pow(10.0, s->leak_log10) *
			     window(th, s->leak_lo_deg, s->leak_hi_deg);
		alpha[i] = a;
		frac[i] = a > 0.0 ? g / a : 0.0;
	}
	for (i = 0; !rc && i < n; i++) {
		for (k = 0; k < n; k++)
			relcov[i * n + k] *= frac[i] * frac[k];
		sigma[i] = alpha[i] * sqrt(fmax(relcov[i * n + i], 0.0));
	}
	free(work);
	free(rc_own);
	return rc;
}
