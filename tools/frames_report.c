/*
 * frames_report.c - what `stray frames` prints of a run of frames
 * (frames/frames_job.h): the false stars per detector against the
 * model, and the lost stars per magnitude, as JSON and as text.
 */
#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "fdr_options.h"
#include "frames_report.h"

static const char *const det_name[2] = { "thesis", "threshold" };

void frames_lost_json(const struct frames_lost *l, cJSON *o)
{
	cJSON *ls = cJSON_AddObjectToObject(o, "lost_stars");
	int d, b;

	for (d = 0; d < 2; d++) {
		cJSON *a = cJSON_AddArrayToObject(ls, det_name[d]);

		for (b = 0; b < FRAMES_LOST_BINS; b++) {
			cJSON *e;
			double n = (double)l->n[b], f;

			if (l->n[b] == 0)
				continue;
			f = l->found[d][b] / n;
			e = cJSON_CreateObject();
			cJSON_AddItemToObject(e, "mag_lo", cli_json_number(
				FRAMES_LOST_MAG0 + b * FRAMES_LOST_STEP));
			cJSON_AddItemToObject(e, "mag_hi", cli_json_number(
				FRAMES_LOST_MAG0 + (b + 1) * FRAMES_LOST_STEP));
			cJSON_AddItemToObject(e, "stars", cli_json_number(n));
			cJSON_AddItemToObject(e, "found", cli_json_number(f));
			cJSON_AddItemToObject(e, "sigma", cli_json_number(
				sqrt(f * (1.0 - f) / n)));
			cJSON_AddItemToObject(e, "model", cli_json_number(
				l->model[d][b] / n));
			cJSON_AddItemToObject(e, "model_nominal", cli_json_number(
				l->nominal[d][b] / n));
			cJSON_AddItemToArray(a, e);
		}
	}
}

void frames_lost_print(const struct frames_lost *l)
{
	int d, b;

	for (d = 0; d < 2; d++)
		for (b = 0; b < FRAMES_LOST_BINS; b++) {
			double n = (double)l->n[b];

			if (l->n[b] < 20)
				continue;
			printf("  %-9s stars m %.2f-%.2f: found %.3f (model %.3f, nominal %.3f) of %ld\n",
			       det_name[d], FRAMES_LOST_MAG0 + b * FRAMES_LOST_STEP,
			       FRAMES_LOST_MAG0 + (b + 1) * FRAMES_LOST_STEP,
			       l->found[d][b] / n, l->model[d][b] / n,
			       l->nominal[d][b] / n, l->n[b]);
		}
}

static double ratio(double model, double measured)
{
	return measured > 0.0 ? model / measured : NAN;
}

static void add_det(cJSON *o, const struct frames_job *st,
		    const struct frames_det_result *r)
{
	cJSON_AddStringToObject(o, "detector", r->name);
	cJSON_AddItemToObject(o, "false_stars_per_image", cli_json_number(r->measured));
	cJSON_AddItemToObject(o, "false_stars_sigma", cli_json_number(r->sigma));
	cJSON_AddItemToObject(o, "false_stars_dispersion", cli_json_number(r->dispersion));
	cJSON_AddItemToObject(o, "model_fdr", cli_json_number(st->rates.model));
	cJSON_AddItemToObject(o, "model_fdr_thesis", cli_json_number(st->rates.thesis));
	cJSON_AddItemToObject(o, "model_fdr_extended", cli_json_number(r->extended));
	cJSON_AddItemToObject(o, "model_fdr_extended_no_map_term", cli_json_number(r->extended_no_map_term));
	cJSON_AddItemToObject(o, "ratio_before", cli_json_number(ratio(st->rates.model, r->measured)));
	cJSON_AddItemToObject(o, "ratio_after", cli_json_number(ratio(r->extended, r->measured)));
	cJSON_AddItemToObject(o, "stars_found_per_image", cli_json_number(r->found));
	cJSON_AddStringToObject(o, "verdict", r->verdict);
}

int frames_print_json(const struct frames_job *st, int detector)
{
	const struct frames_det_result *r = st->res;
	cJSON *o = cJSON_CreateObject(), *ds = cJSON_CreateObject(), *s;
	int top = detector ? 0 : 1, d;

	cJSON_AddStringToObject(o, "sensor", st->s->sensor.name);
	cJSON_AddItemToObject(o, "theta_deg", cli_json_number(st->a.has_theta ? st->a.theta_deg : NAN));
	cJSON_AddItemToObject(o, "alpha", cli_json_number(st->alpha));
	cJSON_AddItemToObject(o, "frames", cli_json_number(st->a.frames));
	cJSON_AddItemToObject(o, "cols", cli_json_number(st->cols));
	cJSON_AddItemToObject(o, "rows", cli_json_number(st->rows));
	fdr_setup_json(st->s, o);
	cJSON_AddStringToObject(o, "stray_light", st->a.map ? st->a.map : "uniform");
	cJSON_AddItemToObject(o, "stray_e_per_px", cli_json_number(st->fm.stray_e));
	cJSON_AddItemToObject(o, "clipped_fraction", cli_json_number(st->clip_frac));
	cJSON_AddItemToObject(o, "bg_resid_rel", cli_json_number(st->resid_rel));
	cJSON_AddItemToObject(o, "threshold_e", cli_json_number(st->fm.i_sdt_e));
	cJSON_AddItemToObject(o, "pixel_threshold_e", cli_json_number(st->fm.pixel_threshold_e));
	cJSON_AddItemToObject(o, "window_px", cli_json_number(st->fm.win.n_px));
	s = cJSON_AddObjectToObject(o, "alpha_required");
	cJSON_AddItemToObject(s, "rate", cli_json_number(st->s->rate));
	cJSON_AddItemToObject(s, "thesis_k1", cli_json_number(st->req.thesis_k1));
	cJSON_AddItemToObject(s, "model", cli_json_number(st->req.model));
	cJSON_AddItemToObject(s, "extended", cli_json_number(st->req.extended));
	s = cJSON_AddObjectToObject(o, "stars");
	cJSON_AddStringToObject(s, "source", st->a.catalogue ?
		"real catalogue (--catalogue) through --attitude" : st->a.has_att ?
		"synthetic catalogue (stray/catalogue.h) through --attitude" :
		"synthetic: all-sky average counts (no catalogue installed)");
	cJSON_AddItemToObject(s, "per_image", cli_json_number(st->stars_sum / st->a.frames));
	cJSON_AddItemToObject(s, "mag_max", cli_json_number(st->a.mag_max));
	add_det(o, st, &r[top]);
	for (d = 0; d < 2; d++)
		add_det(cJSON_AddObjectToObject(ds, r[d].name), st, &r[d]);
	cJSON_AddItemToObject(o, "detectors", ds);
	frames_lost_json(&st->lost, o);
	return cli_json_emit(o);
}

void frames_print_text(const struct frames_job *st)
{
	const struct frames_det_result *r = st->res;
	int d;

	printf("Rendered frames (issue 13) for %s: %d x %d px, %g frames, alpha %.4g\n",
	       st->s->sensor.name, st->cols, st->rows, st->a.frames, st->alpha);
	printf("  normalisation %s, k_px %.3f: %.1f stray e-/px (eq. 2.3), %s\n",
	       stray_normalisation_name(st->s->normalisation), st->k_px,
	       st->fm.stray_e, st->a.map ? st->a.map : "uniform");
	printf("  stars: %s, %.0f per frame to m = %g\n",
	       st->a.catalogue ? "real catalogue through --attitude" :
	       st->a.has_att ? "synthetic catalogue through --attitude"
			     : "synthetic field (no catalogue)",
	       st->stars_sum / st->a.frames, st->a.mag_max);
	printf("  I_sdt %.1f e- (eq. 2.16), pixel threshold %.1f e-\n",
	       st->fm.i_sdt_e, st->fm.pixel_threshold_e);
	printf("  alpha for %g false stars per full image: %.3g (thesis, k_px = 1), %.3g (eq. 2.18 here), %.3g (extended)\n",
	       st->s->rate, st->req.thesis_k1, st->req.model, st->req.extended);
	for (d = 0; d < 2; d++)
		printf("  %-9s false stars %.4g +- %.2g per frame; model %.4g (thesis noise %.4g), extended %.4g\n"
		       "            %s\n", r[d].name, r[d].measured, r[d].sigma,
		       st->rates.model, st->rates.thesis, r[d].extended,
		       r[d].verdict);
	frames_lost_print(&st->lost);
}
