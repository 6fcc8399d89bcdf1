/*
 * diag_report.c - the diagnosis in words: the baseline residual by region,
 * each cause's evidence, the causes named with their intervals and
 * physical explanation, the gain, and what it changes in orbit.
 */
#include <math.h>
#include <stdio.h>

#include "diag_report.h"

static void print_fit_params(const struct diag_fit *f)
{
	int c, k, o = 0;

	for (c = 0; c < f->n_causes; c++) {
		const struct diag_cause *cs = f->cause[c];

		printf("  %s (%s; %s)\n", cs->name, cs->kind == DIAG_REWEIGHT ?
		       "re-weighted paths" : cs->kind == DIAG_RETRACE ?
		       "re-traced geometry" : "measurement model",
		       cs->needs_lens ? "the lens's side" :
		       "the baffle's or the measurement's side");
		if (cs->n_params == 0)
			printf("    (no continuous parameter)\n");
		for (k = 0; k < cs->n_params; k++, o++)
			printf("    %-14s = %-10.4g [%.4g, %.4g] %s (nominal %g)\n",
			       cs->param[k].name, f->p[o], f->ci_lo[o],
			       f->ci_hi[o], cs->param[k].unit,
			       cs->param[k].nominal);
		printf("    %s\n", cs->explanation);
	}
}

static void print_regions(const char *when, const double *rms,
			  const int *count)
{
	int k;

	printf("  RMS log10 residual %s:", when);
	for (k = 0; k < DIAG_REGIONS; k++)
		if (count[k])
			printf("  %s %.3f (%d)", diag_region_name[k], rms[k],
			       count[k]);
	putchar('\n');
}

/* Where the baseline residual sits, in words. */
static void describe_residual(const struct diag_data *d, const double *r,
			      const double *sr)
{
	int k;
	size_t i;

	for (k = 0; k < DIAG_REGIONS; k++) {
		double mean = 0.0, chi = 0.0;
		int n = 0;

		for (i = 0; i < d->n; i++)
			if (d->region[i] == k) {
				mean += r[i];
				chi += (r[i] / sr[i]) * (r[i] / sr[i]);
				n++;
			}
		if (!n)
			continue;
		mean /= n;
		printf("  %-16s measured is %s the model by a factor %.3g "
		       "on average (chi2 %.1f for %d points)\n",
		       diag_region_name[k], mean >= 0 ? "above" : "below",
		       pow(10.0, fabs(mean)), chi, n);
	}
}

/* An exclusion angle, or why there is none within the measured range. */
static void print_angle(double deg)
{
	if (isnan(deg))
		printf("(not excluded by the baffle within the measured "
		       "angles)");
	else
		printf("%.2f deg", deg);
}

void diag_report_text(const struct diag_data *d, const struct diag_eval *e,
		      const struct diag_result *r)
{
	int i;

	printf("Diagnosis of %zu measured angles against scene %s "
	       "(%zu traces, %.1f s of tracing)\n", d->n, e->scene,
	       e->n_traces, e->trace_seconds);
	if (d->normalised)
		printf("The theta 0 row (alpha 1, sigma 0) normalises the "
		       "curve: kept out of the fit.\n");
	for (i = 0; i < e->n_notes; i++)
		printf("Scene: %s\n", e->notes[i]);
	printf("Baseline: chi2 %.1f for %d points, p = %.3g\n",
	       r->chi2_before, r->dof_before, r->p_before);
	describe_residual(d, r->resid_before, r->rsig_before);
	if (!r->significant) {
		printf("No significant discrepancy: the nominal model fits "
		       "the data within the errors (p >= %.2g).\n",
		       DIAG_P_ACCEPT);
		return;
	}
	printf("Each cause alone (BIC = chi2 + k ln n; baseline BIC %.1f):\n",
	       r->chi2_before);
	for (i = 0; i < r->n_single; i++)
		printf("  %-18s chi2 %10.1f  BIC %10.1f  (%+.1f)\n",
		       r->single[i].cause[0]->name, r->single[i].chi2,
		       r->single[i].bic, r->single[i].bic - r->chi2_before);
	if (r->named.n_causes) {
		printf("Named cause(s), each lowering BIC by more than %.0f "
		       "(intervals: profile chi2 + %.0f, 3 sigma):\n",
		       DIAG_BIC_MARGIN, DIAG_CI_DCHI2);
		print_fit_params(&r->named);
	} else if (r->by_surface) {
		printf("The registry's causes leave the residual; the surface "
		       "at fault explains it (p = %.2g, below): its groups are "
		       "the named cause(s).\n", r->p_surface);
	} else if (r->tentative.n_causes) {
		printf("UNEXPLAINED RESIDUAL: the best model of the registry "
		       "still fails (chi2 %.1f for %d dof, p = %.2g); nothing "
		       "is named. Best tentative model:\n", r->chi2_after,
		       r->dof_after, r->p_after);
		print_fit_params(&r->tentative);
	} else {
		printf("UNEXPLAINED RESIDUAL: no cause in the registry earns "
		       "its parameters (BIC margin %.0f).\n", DIAG_BIC_MARGIN);
	}
	if (!r->explained)
		printf("  largest remaining residual at %.2f deg: %+.1f sigma "
		       "(%s)\n", r->worst_theta_deg, r->worst_pull,
		       r->worst_pull > 0 ? "measured above model" :
		       "measured below model");
	if (r->by_surface)
		printf("(The registry's best tentative model below; the "
		       "surface at fault's gain is in its section.)\n");
	printf("Gain: chi2 %.1f -> %.1f (reduced %.2f -> %.2f), RMS log10 "
	       "residual %.3f -> %.3f (x%.1f)\n", r->chi2_before,
	       r->chi2_after, r->chi2_before / r->dof_before,
	       r->dof_after > 0 ? r->chi2_after / r->dof_after : NAN,
	       r->rms_before, r->rms_after,
	       r->rms_after > 0 ? r->rms_before / r->rms_after : INFINITY);
	print_regions("before", r->rms_region_before, r->n_region);
	print_regions("after ", r->rms_region_after, r->n_region);
	printf("In orbit (%s, alpha_required %.3g for the Sun): Sun "
	       "exclusion ", r->sensor, r->sun_alpha_req);
	print_angle(r->sun_deg_before);
	printf(" -> ");
	print_angle(r->sun_deg_after);
	if (r->detector.kind != STRAY_DET_THESIS)	/* thesis: as it was */
		printf(" (detector %s: %s bind)",
		       stray_detector_name(r->detector.kind),
		       r->detector.binding == STRAY_FAIL_LOST_STARS ?
		       "lost stars" : "false stars");
	putchar('\n');
	printf("Approximations: geometry interpolated in log alpha between "
	       "traced nodes; angle offset and beam average from the nominal "
	       "geometry's fine grid; spectral coating over the source x "
	       "response band.\n");
}

void diag_report_surfaces_text(const struct diag_surfaces *s,
			       const char *model)
{
	int k;

	printf("\nSurface at fault (per-group factors by re-weighting the "
	       "path table, %d groups, greedy BIC):\n", s->n_cand);
	if (s->n_named == 0)
		printf("  no surface group lowers BIC by more than %.0f\n",
		       DIAG_BIC_MARGIN);
	for (k = 0; k < s->n_named; k++) {
		int c = s->named[k];

		printf("  %-16s %s x %.3g  [%.3g, %.3g] (%.4g)\n", s->name[c],
		       s->abg[c] ? "ABg A" : "reflectance",
		       pow(10.0, s->log10_f[k]), pow(10.0, s->ci_lo[k]),
		       pow(10.0, s->ci_hi[k]),
		       s->rho[c] * pow(10.0, s->log10_f[k]));
	}
	printf("  RMS log10 residual %.3f -> %.3f (re-weighted), %.3f "
	       "(re-traced); chi2 %.1f -> %.1f, re-traced %.1f\n",
	       s->rms_before, s->rms_after, s->rms_retrace, s->chi2_before,
	       s->chi2_after, s->chi2_retrace);
	if (model)
		printf("  extended model written: %s (trace it with "
		       "`stray trace --scene %s`)\n", model, model);
}
