/*
 * avail_report.c - `stray availability`: the summary (text and --json)
 * and the plots (timeline, false stars, a sky plot per head).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "avail_report.h"
#include "fdrfw/table_build.h"
#include "cli.h"
#include "plot.h"
#include "stray/ccsds.h"

#define TIMELINE_BINS 4000

static cJSON *stats_json(const char *name, const struct stray_avail_stats *s)
{
	static const char *const bins[STRAY_AVAIL_BINS] = {
		"lt_1min", "1_5min", "5_15min", "15_60min", "ge_60min" };
	cJSON *o = cJSON_CreateObject(), *hist = cJSON_CreateObject();
	int b;

	cJSON_AddStringToObject(o, "name", name);
	cJSON_AddNumberToObject(o, "available_frac", s->available_frac);
	cJSON_AddNumberToObject(o, "sun_excluded_frac", s->sun_frac);
	cJSON_AddNumberToObject(o, "moon_excluded_frac", s->moon_frac);
	cJSON_AddNumberToObject(o, "earth_excluded_frac", s->earth_frac);
	cJSON_AddNumberToObject(o, "outages", (double)s->outages);
	cJSON_AddNumberToObject(o, "longest_outage_s", s->longest_outage_s);
	cJSON_AddNumberToObject(o, "mean_outage_s", s->mean_outage_s);
	for (b = 0; b < STRAY_AVAIL_BINS; b++)
		cJSON_AddNumberToObject(hist, bins[b], (double)s->hist[b]);
	cJSON_AddItemToObject(o, "outage_durations", hist);
	return o;
}

int mission_summary(const struct mission_args *a, const struct mission *m)
{
	cJSON *o = cJSON_CreateObject(), *heads = cJSON_CreateArray();
	double amean = 0.0, gap_s = (double)m->any.uncovered * m->step_s;
	size_t h, i;

	for (i = 0; i < m->n; i++)
		if (isfinite(m->albedo[i]))
			amean += m->albedo[i];
	amean /= m->any.epochs ? (double)m->any.epochs : 1.0;
	cJSON_AddStringToObject(o, "oem", a->oem);
	cJSON_AddStringToObject(o, "aem", a->aem);
	cJSON_AddNumberToObject(o, "epochs", (double)m->n);
	cJSON_AddNumberToObject(o, "step_s", m->step_s);
	cJSON_AddNumberToObject(o, "span_s", (double)(m->n - 1) * m->step_s);
	cJSON_AddNumberToObject(o, "mean_earth_albedo", amean);
	/* time in a gap of the OEM or AEM: not flown, in no fraction */
	cJSON_AddNumberToObject(o, "covered_epochs", (double)m->any.epochs);
	cJSON_AddNumberToObject(o, "not_covered_s", gap_s);
	/* gaps inside a segment and time between segments alike */
	cJSON_AddNumberToObject(o, "oem_gaps", (double)stray_ccsds_cover_holes(
		&m->oem.cover, m->oem.t));
	cJSON_AddNumberToObject(o, "aem_gaps", (double)stray_ccsds_cover_holes(
		&m->aem.cover, m->aem.t));
	for (h = 0; h < m->n_heads; h++) {
		const struct mission_head *hd = &m->head[h];
		cJSON *j = stats_json(hd->name, &hd->st);

		cJSON_AddNumberToObject(j, "false_stars_mean", hd->stars_mean);
		cJSON_AddNumberToObject(j, "false_stars_max", hd->stars_max);
		/* the detector its table flies and what binds its Sun angle */
		cJSON_AddStringToObject(j, "detector",
					fdrfw_table_detector_name(&hd->table));
		cJSON_AddStringToObject(j, "binding", stray_failure_mode_name(
					fdrfw_table_binding(&hd->table)));
		cJSON_AddBoolToObject(j, "sun_excluded_by_baffle",
				      hd->sun_excluded);
		if (!hd->sun_excluded)
			cJSON_AddStringToObject(j, "sun_reason", hd->sun_reason);
		cJSON_AddItemToArray(heads, j);
	}
	cJSON_AddItemToObject(o, "heads", heads);
	cJSON_AddNumberToObject(o, "any_head_available_frac", m->any.available_frac);
	cJSON_AddNumberToObject(o, "all_out_outages", (double)m->any.outages);
	cJSON_AddNumberToObject(o, "longest_all_out_s", m->any.longest_outage_s);
	if (cli.json)
		return cli_json_emit(o);
	printf("stray availability: %zu epochs every %g s over %.2f h, %zu heads\n",
	       m->n, m->step_s, (double)(m->n - 1) * m->step_s / 3600.0,
	       m->n_heads);
	if (m->any.uncovered)
		printf("  not covered: %.0f s (%.2f h) in gaps of the OEM/AEM, "
		       "not flown and in no fraction below\n", gap_s,
		       gap_s / 3600.0);
	printf("  mean Earth albedo fed to the flight module %.3f\n", amean);
	printf("  %-8s %9s %7s %7s %7s %7s %10s %9s\n", "head", "available",
	       "sun", "moon", "earth", "outages", "longest_s", "stars_max");
	for (h = 0; h < m->n_heads; h++) {
		const struct mission_head *hd = &m->head[h];

		printf("  %-8s %8.2f%% %6.2f%% %6.2f%% %6.2f%% %7zu %10.0f %9.3g\n",
		       hd->name, 100.0 * hd->st.available_frac,
		       100.0 * hd->st.sun_frac, 100.0 * hd->st.moon_frac,
		       100.0 * hd->st.earth_frac, hd->st.outages,
		       hd->st.longest_outage_s, hd->stars_max);
	}
	printf("  %-8s %8.2f%% %31zu %10.0f\n", "any", 100.0 * m->any.available_frac,
	       m->any.outages, m->any.longest_outage_s);
	for (h = 0; h < m->n_heads; h++)	/* the thesis's text as it was */
		if (m->head[h].table.detector != FDRFW_DET_THESIS)
			printf("  %s: detector %s (its table's grid; %s bind "
			       "the Sun's angle, %.2f deg)\n", m->head[h].name,
			       fdrfw_table_detector_name(&m->head[h].table),
			       fdrfw_table_binding(&m->head[h].table) ==
			       STRAY_FAIL_LOST_STARS ? "lost stars" :
			       "false stars",
			       (double)m->head[h].table.exclusion_sun_deg);
	for (h = 0; h < m->n_heads; h++)
		if (!m->head[h].sun_excluded)
			printf("  %s: the Sun is not excluded by its baffle (%s): "
			       "blind wherever the Sun is in front of it\n",
			       m->head[h].name, m->head[h].sun_reason);
	cJSON_Delete(o);
	return CLI_OK;
}

/* Bins of the timeline: a bin is blind if any epoch in it is; false
 * stars, the bin's largest. */
static int timeline(const struct mission_args *a, const struct mission *m,
		    struct stray_error *err)
{
	size_t nb = m->n < TIMELINE_BINS ? m->n : TIMELINE_BINS, per, b, h, i;
	size_t ns = m->n_heads + 1;
	double *x = calloc(nb, sizeof(double)), *y = calloc(nb * ns, sizeof(double));
	double *f = calloc(nb * m->n_heads, sizeof(double));
	struct plot_series s[MISSION_HEADS_MAX + 1];
	static const enum plot_color col[] = { PLOT_BLUE, PLOT_RED, PLOT_GREEN,
		PLOT_ORANGE, PLOT_PURPLE, PLOT_GREY, PLOT_BLACK, PLOT_BLUE };
	char path[4096];
	int rc = STRAY_ENOMEM;

	if (!x || !y || !f)
		goto done;
	per = (m->n + nb - 1) / nb;
	nb = (m->n + per - 1) / per;
	for (b = 0; b < nb; b++) {
		x[b] = (double)(b * per) * m->step_s / 3600.0;
		for (h = 0; h < ns; h++) {
			int blind = 0;
			double mx = 0.0;

			for (i = b * per; i < (b + 1) * per && i < m->n; i++) {
				blind |= (h < m->n_heads ? m->head[h].mask[i] :
					  m->any_mask[i]) != 0;
				if (h < m->n_heads && isfinite(m->head[h].stars[i]))
					mx = fmax(mx, m->head[h].stars[i]);
			}
			y[h * nb + b] = (double)(ns - 1 - h) + (blind ? 0.0 : 0.7);
			if (h < m->n_heads)
				f[h * nb + b] = mx;
		}
	}
	for (h = 0; h < ns; h++) {
		s[h] = (struct plot_series){ x, y + h * nb, nb, NULL, NULL,
			h < m->n_heads ? col[h] : PLOT_BLACK, PLOT_LINE,
			h < m->n_heads ? m->head[h].name : "any head" };
	}
	{
		struct plot_spec p = { path, "Availability per head (high: available, low: blind)",
			"time [h]", "head (top first); any head at the bottom", 0, 0,
			0.0, NAN, -0.2, (double)ns, s, ns, 0 };

		snprintf(path, sizeof(path), "%s_timeline.png", a->plot);
		if ((rc = plot_render(&p, err)) != STRAY_OK)
			goto done;
	}
	for (h = 0; h < m->n_heads; h++)
		s[h] = (struct plot_series){ x, f + h * nb, nb, NULL, NULL,
			col[h], PLOT_LINE, m->head[h].name };
	{
		struct plot_spec p = { path, "Predicted false stars per frame (largest in each bin)",
			"time [h]", "false stars per frame", 0, 1, 0.0, NAN,
			1e-6, 1e6, s, m->n_heads, 0 };

		snprintf(path, sizeof(path), "%s_fdr.png", a->plot);
		rc = plot_render(&p, err);
	}
done:
	free(x);
	free(y);
	free(f);
	return rc;
}

static int sky(const struct mission_args *a, const struct mission *m,
	       size_t h, struct stray_error *err)
{
	const struct mission_head *hd = &m->head[h];
	double cx[2][73], cy[2][73], rad[2] = { hd->table.exclusion_sun_deg,
						hd->table.fov_half_deg };
	char path[4096];
	int k, c;

	for (c = 0; c < 2; c++)
		for (k = 0; k < 73; k++) {
			cx[c][k] = rad[c] * cos(k * 5.0 * 0.0174532925199433);
			cy[c][k] = rad[c] * sin(k * 5.0 * 0.0174532925199433);
		}
	{
		const struct plot_series s[] = {
			{ hd->sky[0][0], hd->sky[0][1], m->n_sky, NULL, NULL, PLOT_RED, PLOT_POINTS, "Sun" },
			{ hd->sky[1][0], hd->sky[1][1], m->n_sky, NULL, NULL, PLOT_GREY, PLOT_POINTS, "Moon" },
			{ hd->sky[2][0], hd->sky[2][1], m->n_sky, NULL, NULL, PLOT_GREEN, PLOT_POINTS, "Earth limb (nearest)" },
			{ cx[0], cy[0], 73, NULL, NULL, PLOT_RED, PLOT_DASHED, "Sun exclusion cone" },
			{ cx[1], cy[1], 73, NULL, NULL, PLOT_BLUE, PLOT_LINE, "field of view" },
		};
		char title[128];
		struct plot_spec p = { path, title,
			"off-axis angle x [deg] (azimuthal equidistant)",
			"off-axis angle y [deg]", 0, 0, -180.0, 180.0, -180.0, 180.0, s, 5, 0 };

		snprintf(title, sizeof(title), "Sky of head %s: paths in its frame", hd->name);
		snprintf(path, sizeof(path), "%s_sky_%s.png", a->plot, hd->name);
		return plot_render(&p, err);
	}
}

int mission_plot(const struct mission_args *a, const struct mission *m,
		 struct stray_error *err)
{
	size_t h;
	int rc = timeline(a, m, err);

	for (h = 0; rc == STRAY_OK && h < m->n_heads; h++)
		rc = sky(a, m, h, err);
	return rc;
}
