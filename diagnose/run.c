/*
 * run.c - the diagnosis: baseline, each cause alone, greedy combinations
 * ranked by BIC, intervals, the gain.
 *
 * Decisions (stated in the report):
 *   - "no significant discrepancy" when the baseline chi2 has
 *     p >= DIAG_P_ACCEPT;
 *   - a cause enters (alone, or added to those already named) only when it
 *     lowers BIC = chi2 + k ln n by more than DIAG_BIC_MARGIN (Kass &
 *     Raftery 1995: "very strong" evidence), and leaves again when the
 *     others explain the data without it;
 *   - when even the best model fails (p < DIAG_P_FINAL) nothing is
 *     named: the best model is reported as tentative, with the residual
 *     that remains and where it sits.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "candidates.h"
#include "diagnose/diag_result.h"
#include "diagnose/diag_surfaces.h"
#include "stray/errfmt.h"

#define P_FINAL 1e-3	/* the best model must not fail worse than this */
#define IN_FIELD_DEG 10.0	/* st16-like field half-angle (ref4-baffle.md) */
#define TRANSITION_SHARE 1e-3	/* direct light still a part of the total */

static void say(void (*log)(const char *), const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

static void say(void (*log)(const char *), const char *fmt, ...)
{
	char line[256];
	va_list ap;

	if (!log)
		return;
	va_start(ap, fmt);
	vsnprintf(line, sizeof(line), fmt, ap);
	va_end(ap);
	log(line);
}

static void assign_regions(const struct diag_eval *e,
			   const struct diag_data *d)
{
	size_t i;

	for (i = 0; i < d->n; i++)
		d->region[i] = d->theta_deg[i] <= IN_FIELD_DEG ? DIAG_IN_FIELD :
			e->direct_share[i] > TRANSITION_SHARE ?
			DIAG_TRANSITION : DIAG_SCATTER;
}

static void rms(const struct diag_data *d, const double *r, double *all,
		double *region, int *count)
{
	double s = 0.0, sr[DIAG_REGIONS] = { 0 };
	size_t i;
	int k;

	for (k = 0; k < DIAG_REGIONS; k++)
		count[k] = 0;
	for (i = 0; i < d->n; i++) {
		s += r[i] * r[i];
		sr[d->region[i]] += r[i] * r[i];
		count[d->region[i]]++;
	}
	*all = sqrt(s / d->n);
	for (k = 0; k < DIAG_REGIONS; k++)
		region[k] = count[k] ? sqrt(sr[k] / count[k]) : NAN;
}

/* A stage's cost, said in the log (issue 27: where the time goes): the
 * traces it added, their seconds, and its wall time with the fits. */
struct stage {
	size_t traces;
	double trace_s, t0, cpu0;
};

static double clock_s(clockid_t id)
{
	struct timespec ts;

	clock_gettime(id, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void stage_start(const struct diag_eval *e, struct stage *g)
{
	g->traces = e->n_traces;
	g->trace_s = e->trace_seconds;
	g->t0 = clock_s(CLOCK_MONOTONIC);
	g->cpu0 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
}

/* cpu: this process's threads (a shared machine's wall clock counts the
 * other processes too) */
static void stage_say(const struct diag_eval *e, const struct stage *g,
		      void (*log)(const char *), const char *what)
{
	say(log, "    [%s: %zu traces, %.2f s tracing, %.2f s wall, "
	    "%.2f s cpu in all]", what, e->n_traces - g->traces,
	    e->trace_seconds - g->trace_s,
	    clock_s(CLOCK_MONOTONIC) - g->t0,
	    clock_s(CLOCK_PROCESS_CPUTIME_ID) - g->cpu0);
}

static int uses(const struct diag_fit *f, const struct diag_cause *c)
{
	int i;

	for (i = 0; i < f->n_causes; i++)
		if (f->cause[i] == c)
			return 1;
	return 0;
}

static int earned_alone(const struct diag_result *r,
			const struct diag_cause *c)
{
	int i;

	for (i = 0; i < r->n_single; i++)
		if (r->single[i].cause[0] == c)
			return r->chi2_before - r->single[i].bic >
			       DIAG_BIC_MARGIN;
	return 0;
}

static int usable(const struct diag_eval *e, const struct diag_cause *c)
{
	size_t i;

	if (c->needs_lens && !e->lens)
		return 0;
	if (c->needs_unnormalised && e->normalised)
		return 0;
	for (i = 0; c->needs_unnormalised && i < e->n; i++)
		if (e->theta_deg[i] == 0.0)
			return 0;
	return e->parametric || !c->needs_baffle;
}

/* A cause of the registry fitted to the scene, by name, or NULL. */
static const struct diag_cause *scene_cause(const struct diag_eval *e,
					    const char *name)
{
	int i;

	for (i = 0; e->causes[i]; i++)
		if (strcmp(e->causes[i]->name, name) == 0)
			return e->causes[i];
	return NULL;
}

/* Would c's grid have to be traced at other geometries of cur (a
 * re-trace cause joining another one)?  Such a candidate goes through the
 * screen (candidates.c): its combined grid costs a trace per node pair (a
 * pivot-offset pass, eight nominal traces' time, per node of the other
 * axis), so it is first fitted with the interaction neglected
 * (geometry_blend.c, no trace) and traced only when that lowers BIC by at
 * least half the margin. */
static int needs_combined_grid(const struct diag_fit *cur,
			       const struct diag_cause *c)
{
	int i;

	if (c->kind != DIAG_RETRACE)
		return 0;
	for (i = 0; i < cur->n_causes; i++)
		if (cur->cause[i]->kind == DIAG_RETRACE &&
		    cur->cause[i]->geo_axis != c->geo_axis)
			return 1;
	return 0;
}

/* Greedy forward steps from `cur`; each must lower BIC by the margin.
 * Candidates are the causes that earned their place alone (a cause that
 * cannot improve the baseline by itself is not tried in combination: it
 * saves the traces of its grid). */
static int forward(struct diag_eval *e, const struct diag_data *d,
		   const struct diag_result *r, struct diag_fit *cur,
		   void (*log)(const char *), struct stray_error *err)
{
	int i, rc = STRAY_OK;

	while (cur->n_causes < DIAG_COMBO_MAX && !rc) {
		struct diag_candidate c[DIAG_CAUSES_MAX];
		struct diag_fit best;
		int n = 0;

		for (i = 0; e->causes[i] && n < DIAG_CAUSES_MAX; i++) {
			if (uses(cur, e->causes[i]) ||
			    !usable(e, e->causes[i]) ||
			    !earned_alone(r, e->causes[i]))
				continue;
			c[n].f = *cur;
			c[n].f.cause[c[n].f.n_causes++] = e->causes[i];
			c[n++].combined = needs_combined_grid(cur,
							      e->causes[i]);
		}
		rc = diag_fit_candidates(e, d, cur->bic, c, n, err);
		best.bic = INFINITY;
		for (i = 0; i < n && !rc; i++) {
			if (c[i].screened) {
				say(log, "  (%s: BIC %.1f -> %.1f with the "
				    "interaction neglected; its combined grid "
				    "not traced)",
				    c[i].f.cause[c[i].f.n_causes - 1]->name,
				    cur->bic, c[i].screen_bic);
				continue;
			}
			if (c[i].f.bic < best.bic)
				best = c[i].f;
		}
		if (rc || !(cur->bic - best.bic > DIAG_BIC_MARGIN))
			break;
		say(log, "  + %s: BIC %.1f -> %.1f", best.cause[best.n_causes - 1]->name,
		    cur->bic, best.bic);
		*cur = best;
	}
	return rc;
}

/* f: cur without its cause i, the others' parameters kept (in order). */
static void without(const struct diag_fit *cur, int i, struct diag_fit *f)
{
	int j, k, o = 0, q = 0;

	memset(f, 0, sizeof(*f));
	for (j = 0; j < cur->n_causes; j++) {
		int np = cur->cause[j]->n_params;

		if (j != i) {
			f->cause[f->n_causes++] = cur->cause[j];
			for (k = 0; k < np; k++)
				f->p[q++] = cur->p[o + k];
		}
		o += np;
	}
}

/* Drop causes the others make redundant (BIC not worse by the margin). */
static int backward(struct diag_eval *e, const struct diag_data *d,
		    struct diag_fit *cur, void (*log)(const char *),
		    struct stray_error *err)
{
	int i, rc = STRAY_OK;

	for (i = 0; cur->n_causes > 1 && i < cur->n_causes && !rc; i++) {
		struct diag_fit f;

		without(cur, i, &f);
		/* the last kept cause restarts from its grid */
		rc = diag_fit_run(e, d, &f, 1, err);
		if (!rc && f.bic - cur->bic < DIAG_BIC_MARGIN) {
			say(log, "  - %s: redundant (BIC %.1f -> %.1f)",
			    cur->cause[i]->name, cur->bic, f.bic);
			*cur = f;
			i = -1;
		}
	}
	return rc;
}

/* A named extension (spectral_slope, beam_profile) gives way to the
 * simpler cause it nests unless it lowers BIC by the margin. */
static int simplify(struct diag_eval *e, const struct diag_data *d,
		    struct diag_fit *cur, void (*log)(const char *),
		    struct stray_error *err)
{
	int i, rc = STRAY_OK;

	for (i = 0; i < cur->n_causes && !rc; i++) {
		const struct diag_cause *c = cur->cause[i], *s;
		struct diag_fit f;

		s = c->nests ? scene_cause(e, c->nests) : NULL;
		if (!s || uses(cur, s) || !usable(e, s))
			continue;
		without(cur, i, &f);
		f.cause[f.n_causes++] = s;	/* from its grid */
		rc = diag_fit_run(e, d, &f, 1, err);
		if (!rc && f.bic - cur->bic < DIAG_BIC_MARGIN) {
			say(log, "  %s -> %s: the extension is not needed "
			    "(BIC %.1f -> %.1f)", c->name, s->name, cur->bic,
			    f.bic);
			*cur = f;
			i = -1;
		}
	}
	return rc;
}

/* Each cause alone.  The re-trace causes are traced and fitted here in
 * turn, the others fitted meanwhile on a second thread (candidates.c);
 * the table and the log keep the registry's order. */
static int fit_singles(struct diag_eval *e, const struct diag_data *d,
		       struct diag_result *r, void (*log)(const char *),
		       struct stray_error *err)
{
	struct diag_candidate c[DIAG_CAUSES_MAX];
	struct stage g[DIAG_CAUSES_MAX], all;
	double wall[DIAG_CAUSES_MAX];
	struct diag_aside a;
	int i, n_aside = 0, at[DIAG_CAUSES_MAX], rc;

	r->n_single = 0;
	stage_start(e, &all);
	for (i = 0; e->causes[i] && r->n_single < DIAG_CAUSES_MAX; i++) {
		struct diag_fit *f = &r->single[r->n_single];

		if (!usable(e, e->causes[i]))
			continue;
		memset(f, 0, sizeof(*f));
		f->n_causes = 1;
		f->cause[0] = e->causes[i];
		if (e->causes[i]->kind != DIAG_RETRACE) {
			memset(&c[n_aside], 0, sizeof(c[n_aside]));
			c[n_aside].f = *f;
			at[n_aside++] = r->n_single;
		}
		r->n_single++;
	}
	rc = diag_aside_start(&a, e, d, c, n_aside, err);
	for (i = 0; i < r->n_single && !rc; i++) {
		if (r->single[i].cause[0]->kind != DIAG_RETRACE)
			continue;
		stage_start(e, &g[i]);
		rc = diag_fit_run(e, d, &r->single[i], 0, err);
		wall[i] = clock_s(CLOCK_MONOTONIC) - g[i].t0;
		g[i].traces = e->n_traces - g[i].traces;
		g[i].trace_s = e->trace_seconds - g[i].trace_s;
	}
	rc = diag_aside_finish(&a, e, d, c, n_aside, rc, err);
	for (i = 0; i < n_aside && !rc; i++)
		r->single[at[i]] = c[i].f;
	for (i = 0; i < r->n_single && !rc; i++) {
		const struct diag_fit *f = &r->single[i];

		say(log, "  %-18s chi2 %10.1f  BIC %10.1f", f->cause[0]->name,
		    f->chi2, f->bic);
		if (f->cause[0]->kind == DIAG_RETRACE)
			say(log, "    [%s: %zu traces, %.2f s tracing, %.2f s "
			    "wall]", f->cause[0]->name, g[i].traces,
			    g[i].trace_s, wall[i]);
	}
	if (!rc)
		stage_say(e, &all, log, "each cause alone");
	return rc;
}

static int final_curves(struct diag_eval *e, const struct diag_data *d,
			struct diag_result *r, const struct diag_fit *f,
			struct stray_error *err)
{
	struct diag_state s;
	double chi2;
	size_t i;
	int rc;

	diag_fit_state(f, f->p, &s);
	rc = diag_chi2(e, d, &s, &chi2, r->resid_after, r->rsig_after,
		       r->model_after, NULL, err);
	r->chi2_after = chi2;
	r->dof_after = (int)d->n - f->k;
	r->p_after = diag_chi2_pvalue(chi2, r->dof_after);
	rms(d, r->resid_after, &r->rms_after, r->rms_region_after,
	    r->n_region);
	r->worst_pull = 0.0;
	for (i = 0; i < d->n; i++) {
		double pull = r->resid_after[i] / r->rsig_after[i];

		if (fabs(pull) > fabs(r->worst_pull)) {
			r->worst_pull = pull;
			r->worst_theta_deg = d->theta_deg[i];
		}
	}
	return rc;
}

static int alloc_result(struct diag_result *r, size_t n,
			struct stray_error *err)
{
	double *m = calloc(6 * n, sizeof(*m));

	memset(r, 0, sizeof(*r));
	if (!m)
		return stray_error_set(err, STRAY_ENOMEM, "diagnose",
				       "out of memory");
	r->model_before = m;
	r->model_after = m + n;
	r->resid_before = m + 2 * n;
	r->resid_after = m + 3 * n;
	r->rsig_before = m + 4 * n;
	r->rsig_after = m + 5 * n;
	return STRAY_OK;
}

static int name_causes(struct diag_eval *e, const struct diag_data *d,
		       struct diag_result *r, double bic0,
		       void (*log)(const char *), struct stray_error *err)
{
	struct diag_fit cur;
	struct stage g;
	int i, rc;

	memset(&cur, 0, sizeof(cur));
	cur.bic = bic0;
	for (i = 0; i < r->n_single; i++)
		if (bic0 - r->single[i].bic > DIAG_BIC_MARGIN &&
		    r->single[i].bic < cur.bic)
			cur = r->single[i];
	if (cur.n_causes == 0) {
		say(log, "no cause lowers BIC by more than %.0f",
		    DIAG_BIC_MARGIN);
		return STRAY_OK;
	}
	say(log, "greedy combinations from %s:", cur.cause[0]->name);
	stage_start(e, &g);
	rc = forward(e, d, r, &cur, log, err);
	if (!rc)
		rc = backward(e, d, &cur, log, err);
	if (!rc)
		rc = simplify(e, d, &cur, log, err);
	if (!rc) {
		stage_say(e, &g, log, "combinations");
		stage_start(e, &g);
		rc = diag_fit_intervals(e, d, &cur, err);
	}
	if (rc)
		return rc;
	stage_say(e, &g, log, "intervals");
	r->explained = diag_chi2_pvalue(cur.chi2, (int)d->n - cur.k) >= P_FINAL;
	if (r->explained)
		r->named = cur;
	else
		r->tentative = cur;
	return final_curves(e, d, r, &cur, err);
}

int diag_run(struct diag_eval *e, const struct diag_data *d,
	     struct diag_result *r, void (*log)(const char *),
	     struct stray_error *err)
{
	struct diag_state s;
	int rc = alloc_result(r, d->n, err);

	if (rc)
		return rc;
	assign_regions(e, d);
	diag_state_nominal(&s);
	rc = diag_chi2(e, d, &s, &r->chi2_before, r->resid_before,
		       r->rsig_before, r->model_before, NULL, err);
	if (rc)
		return rc;
	r->dof_before = (int)d->n;
	r->p_before = diag_chi2_pvalue(r->chi2_before, r->dof_before);
	rms(d, r->resid_before, &r->rms_before, r->rms_region_before,
	    r->n_region);
	r->significant = r->p_before < DIAG_P_ACCEPT;
	say(log, "baseline: chi2 %.1f for %d points (p = %.3g)",
	    r->chi2_before, r->dof_before, r->p_before);
	say(log, "    [nominal: %zu traces, %.2f s tracing]", e->n_traces,
	    e->trace_seconds);
	/* defaults: the corrected model is the baseline */
	memcpy(r->model_after, r->model_before, d->n * sizeof(double));
	memcpy(r->resid_after, r->resid_before, d->n * sizeof(double));
	memcpy(r->rsig_after, r->rsig_before, d->n * sizeof(double));
	r->chi2_after = r->chi2_before;
	r->dof_after = r->dof_before;
	r->p_after = r->p_before;
	r->rms_after = r->rms_before;
	memcpy(r->rms_region_after, r->rms_region_before,
	       sizeof(r->rms_region_after));
	r->explained = !r->significant;
	if (r->significant) {
		say(log, "each cause alone:");
		rc = fit_singles(e, d, r, log, err);
		if (!rc)
			rc = name_causes(e, d, r, r->chi2_before, log, err);
	}
	if (!rc && r->named.n_causes == 0 && r->tentative.n_causes == 0) {
		struct diag_fit none;

		memset(&none, 0, sizeof(none));
		rc = final_curves(e, d, r, &none, err);
	}
	r->detector.name = e->detector;
	r->detector.kind = STRAY_DET_THESIS;
	r->detector.sigma = e->detector_sigma;
	if (e->detector)
		stray_detector_parse(e->detector, &r->detector.kind, NULL);
	if (!rc)
		rc = diag_sun_exclusion_det(e->sensor, &r->detector,
					d->theta_deg, r->model_before, d->n,
					&r->sun_deg_before, &r->sun_alpha_req,
					r->sensor, err);
	if (!rc)
		rc = diag_sun_exclusion_det(e->sensor, &r->detector,
					d->theta_deg, r->model_after, d->n,
					&r->sun_deg_after, &r->sun_alpha_req,
					NULL, err);
	return rc;
}

int diag_result_surfaces(struct diag_result *r,
			 const struct diag_surfaces *s)
{
	int dof = s->n_fit - s->n_named;
	double p;

	if (r->explained || !r->significant || s->n_named == 0 || dof <= 0)
		return 0;
	p = diag_chi2_pvalue(s->chi2_after, dof);
	if (!(p >= DIAG_P_ACCEPT))
		return 0;
	r->by_surface = 1;
	r->p_surface = p;
	r->explained = 1;
	return 1;
}

void diag_result_free(struct diag_result *r)
{
	free(r->model_before);
	memset(r, 0, sizeof(*r));
}
