/*
 * design_report.c - the outputs of `stray sweep`: a text table, a CSV
 * (written atomically), JSON and a plot of the Sun exclusion angle per
 * design with its alpha -/+ sigma interval.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "cli.h"
#include "design_sweep.h"
#include "plot.h"
#include "stray/file.h"

void design_best_worst(const struct sweep_summary *s, long *best,
		       long *worst, long *second)
{
	size_t i;

	*best = *worst = *second = -1;
	for (i = 0; i < s->n; i++) {
		double v = s->d[i].sun_deg;

		if (!isfinite(v))
			continue;
		if (*best < 0 || v < s->d[*best].sun_deg) {
			*second = *best;
			*best = (long)i;
		} else if (*second < 0 || v < s->d[*second].sun_deg) {
			*second = (long)i;
		}
		if (*worst < 0 || v > s->d[*worst].sun_deg)
			*worst = (long)i;
	}
}

int design_write_csv(const struct sweep_summary *s, const char *path,
		     struct stray_error *err)
{
	struct stray_file_out out;
	size_t i;
	int k, rc = stray_file_open_atomic(&out, path, err);

	if (rc)
		return rc;
	fprintf(out.f, "# stray sweep: Sun exclusion angle per design "
		"(sensor %s, alpha_required %.6g)\n", s->sensor, s->alpha_req);
	for (i = 0; i < s->n; i++)
		fprintf(out.f, "# design %zu: %s\n", i, s->d[i].label);
	fprintf(out.f, "design,sun_deg,sun_deg_lo,sun_deg_hi");
	for (k = 0; k < s->n_at; k++)
		fprintf(out.f, ",alpha_at_%g", s->at_deg[k]);
	fputc('\n', out.f);
	for (i = 0; i < s->n; i++) {
		const struct design_result *d = &s->d[i];

		fprintf(out.f, "%zu,%.17g,%.17g,%.17g", i, d->sun_deg,
			d->sun_lo_deg, d->sun_hi_deg);
		for (k = 0; k < s->n_at; k++)
			fprintf(out.f, ",%.17g", d->alpha_at[k]);
		fputc('\n', out.f);
	}
	return stray_file_commit(&out, err);
}

static size_t excluded_count(const struct sweep_summary *s)
{
	size_t i, n = 0;

	for (i = 0; i < s->n; i++)
		n += isfinite(s->d[i].sun_deg) != 0;
	return n;
}

void design_print_text(const struct sweep_summary *s)
{
	long best, worst, second;
	size_t i;
	int k;

	printf("Sun exclusion angle per design (sensor %s, alpha_required "
	       "%.3g with k_px %.4g, %s; interval from alpha -/+ sigma)\n",
	       s->sensor, s->alpha_req, s->k_px, s->normalisation);
	if (strcmp(s->detector, "thesis") != 0)	/* the thesis's text as it was */
		printf("detector %s: alpha_required where %s bind first "
		       "(docs/detectors.md)\n", s->detector,
		       strcmp(s->binding, "lost_stars") == 0 ? "lost stars" :
		       "false stars");
	printf("%-4s %8s %15s", "#", "sun_deg", "interval");
	for (k = 0; k < s->n_at; k++)
		printf("  alpha@%-5g", s->at_deg[k]);
	printf("  design\n");
	for (i = 0; i < s->n; i++) {
		const struct design_result *d = &s->d[i];

		if (isfinite(d->sun_deg))
			printf("%-4zu %8.2f  [%5.2f, %5.2f]", i, d->sun_deg,
			       d->sun_lo_deg, d->sun_hi_deg);
		else	/* libstray's verdict: not excluded by the baffle */
			printf("%-4zu %8s  %15s", i, "none", "(not excluded)");
		for (k = 0; k < s->n_at; k++)
			printf("  %11.3e", d->alpha_at[k]);
		printf("  %s%s\n", d->label, d->resumed ? " (resumed)" : "");
	}
	design_best_worst(s, &best, &worst, &second);
	if (best < 0)
		printf("no design keeps alpha below alpha_required within the "
		       "traced angles (Sun not excluded)\n");
	if (best >= 0)
		printf("best: design %ld (%s): %.2f deg", best,
		       s->d[best].label, s->d[best].sun_deg);
	if (best >= 0 && second >= 0)
		printf("; %.2f deg better than the worst (design %ld), %.2f deg "
		       "better than the runner-up (design %ld)",
		       s->d[worst].sun_deg - s->d[best].sun_deg, worst,
		       s->d[second].sun_deg - s->d[best].sun_deg, second);
	if (best >= 0)
		printf("%s\n", excluded_count(s) < s->n ? "; the others with "
		       "sun_deg none (JSON null) are not excluded by the baffle" :
		       "");
}

int design_print_json(const struct sweep_summary *s)
{
	cJSON *o = cJSON_CreateObject(), *arr = cJSON_CreateArray();
	long best, worst, second;
	size_t i;
	int k;

	cJSON_AddStringToObject(o, "sensor", s->sensor);
	cJSON_AddItemToObject(o, "alpha_required",
			      cli_json_number(s->alpha_req));
	cJSON_AddStringToObject(o, "normalisation", s->normalisation);
	cJSON_AddItemToObject(o, "k_px", cli_json_number(s->k_px));
	cJSON_AddStringToObject(o, "detector", s->detector);
	cJSON_AddStringToObject(o, "binding", s->binding);
	for (i = 0; i < s->n; i++) {
		const struct design_result *d = &s->d[i];
		cJSON *e = cJSON_CreateObject(), *at = cJSON_CreateObject();
		char name[32];

		cJSON_AddNumberToObject(e, "design", (double)i);
		cJSON_AddStringToObject(e, "settings", d->label);
		cJSON_AddItemToObject(e, "sun_deg", cli_json_number(d->sun_deg));
		cJSON_AddBoolToObject(e, "excluded", isfinite(d->sun_deg));
		cJSON_AddItemToObject(e, "sun_deg_lo",
				      cli_json_number(d->sun_lo_deg));
		cJSON_AddItemToObject(e, "sun_deg_hi",
				      cli_json_number(d->sun_hi_deg));
		for (k = 0; k < s->n_at; k++) {
			snprintf(name, sizeof(name), "%g", s->at_deg[k]);
			cJSON_AddItemToObject(at, name,
					      cli_json_number(d->alpha_at[k]));
		}
		cJSON_AddItemToObject(e, "alpha_at", at);
		cJSON_AddBoolToObject(e, "resumed", d->resumed);
		cJSON_AddItemToArray(arr, e);
	}
	cJSON_AddItemToObject(o, "designs", arr);
	design_best_worst(s, &best, &worst, &second);
	if (best >= 0) {
		cJSON_AddNumberToObject(o, "best", (double)best);
		cJSON_AddItemToObject(o, "margin_over_worst_deg",
			cli_json_number(s->d[worst].sun_deg -
					s->d[best].sun_deg));
		cJSON_AddItemToObject(o, "margin_over_second_deg",
			cli_json_number(second >= 0 ? s->d[second].sun_deg -
					s->d[best].sun_deg : NAN));
	}
	return cli_json_emit(o);
}

int design_plot(const struct sweep_summary *s, const char *path,
		struct stray_error *err)
{
	double *x = malloc(4 * s->n * sizeof(double));
	struct plot_series ser;
	struct plot_spec sp = { path, "stray sweep: Sun exclusion angle per "
				"design", "design", "Sun exclusion angle (deg)",
				0, 0, -0.5, s->n - 0.5, NAN, NAN, &ser, 1, 0 };
	size_t i;
	int rc;

	if (!x)
		return stray_error_set(err, STRAY_ENOMEM, "--plot",
				       "out of memory");
	for (i = 0; i < s->n; i++) {
		x[i] = (double)i;
		x[s->n + i] = s->d[i].sun_deg;
		x[2 * s->n + i] = s->d[i].sun_lo_deg;
		x[3 * s->n + i] = s->d[i].sun_hi_deg;
	}
	ser = (struct plot_series){ x, x + s->n, s->n, x + 2 * s->n,
				    x + 3 * s->n, PLOT_BLUE, PLOT_POINTS,
				    "alpha -/+ sigma interval" };
	rc = plot_render(&sp, err);
	free(x);
	return rc;
}
