/*
 * diag_json.c - `stray diagnose --json` (docs/cli.md): `causes` (list of
 * {name, params}), `rms_before`, `rms_after`, `significant`, and the rest
 * of the diagnosis.
 */
#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "diag_report.h"

static cJSON *fit_json(const struct diag_fit *f)
{
	cJSON *list = cJSON_CreateArray();
	int c, k, o = 0;

	for (c = 0; c < f->n_causes; c++) {
		const struct diag_cause *cs = f->cause[c];
		cJSON *it = cJSON_CreateObject(), *p = cJSON_CreateObject();
		cJSON *ci = cJSON_CreateObject(), *nom = cJSON_CreateObject();

		cJSON_AddStringToObject(it, "name", cs->name);
		cJSON_AddStringToObject(it, "side", cs->needs_lens ? "lens" :
					"baffle or measurement");
		for (k = 0; k < cs->n_params; k++, o++) {
			cJSON *pair = cJSON_CreateArray();

			/* the scene's own value (diagnose/scene_causes.c) */
			cJSON_AddItemToObject(nom, cs->param[k].name,
					      cli_json_number(cs->param[k].nominal));

			cJSON_AddItemToObject(p, cs->param[k].name,
					      cli_json_number(f->p[o]));
			cJSON_AddItemToArray(pair, cli_json_number(f->ci_lo[o]));
			cJSON_AddItemToArray(pair, cli_json_number(f->ci_hi[o]));
			cJSON_AddItemToObject(ci, cs->param[k].name, pair);
		}
		cJSON_AddItemToObject(it, "params", p);
		cJSON_AddItemToObject(it, "intervals", ci);
		cJSON_AddItemToObject(it, "nominal", nom);
		cJSON_AddItemToArray(list, it);
	}
	return list;
}

/* The surface groups at fault as named causes (diag_result_surfaces). */
static void surface_causes(cJSON *list, const struct diag_surfaces *s)
{
	int k;

	for (k = 0; k < s->n_named; k++) {
		cJSON *it = cJSON_CreateObject(), *p = cJSON_CreateObject();
		cJSON *ci = cJSON_CreateObject(), *pair = cJSON_CreateArray();
		cJSON *rpair = cJSON_CreateArray(), *nom = cJSON_CreateObject();
		int c = s->named[k];

		cJSON_AddStringToObject(it, "name", s->abg[c] ?
			"surface_abg_scale" : "surface_reflectance");
		cJSON_AddStringToObject(it, "surface", s->name[c]);
		cJSON_AddStringToObject(it, "side", "baffle or measurement");
		cJSON_AddItemToObject(p, "factor",
				      cli_json_number(pow(10.0, s->log10_f[k])));
		cJSON_AddItemToObject(p, "reflectance", cli_json_number(
			s->rho[c] * pow(10.0, s->log10_f[k])));
		cJSON_AddItemToObject(nom, "factor", cJSON_CreateNumber(1.0));
		cJSON_AddItemToObject(nom, "reflectance",
				      cli_json_number(s->rho[c]));
		cJSON_AddItemToArray(pair, cli_json_number(pow(10.0, s->ci_lo[k])));
		cJSON_AddItemToArray(pair, cli_json_number(pow(10.0, s->ci_hi[k])));
		cJSON_AddItemToArray(rpair, cli_json_number(s->rho[c] *
						pow(10.0, s->ci_lo[k])));
		cJSON_AddItemToArray(rpair, cli_json_number(s->rho[c] *
						pow(10.0, s->ci_hi[k])));
		cJSON_AddItemToObject(ci, "factor", pair);
		cJSON_AddItemToObject(ci, "reflectance", rpair);
		cJSON_AddItemToObject(it, "params", p);
		cJSON_AddItemToObject(it, "intervals", ci);
		cJSON_AddItemToObject(it, "nominal", nom);
		cJSON_AddItemToArray(list, it);
	}
}

static cJSON *regions_json(const double *rms, const int *count)
{
	cJSON *o = cJSON_CreateObject();
	static const char *const key[DIAG_REGIONS] = {
		"in_field", "transition", "scatter"
	};
	int k;

	for (k = 0; k < DIAG_REGIONS; k++)
		if (count[k])
			cJSON_AddItemToObject(o, key[k], cli_json_number(rms[k]));
	return o;
}

/* The curves of the plot (issue 32: a notebook redraws it from --json):
 * the measured points and the model before and after, one value each. */
static cJSON *curves_json(const struct diag_data *d,
			  const struct diag_result *r)
{
	const double *col[5] = { d->theta_deg, d->alpha, d->sigma,
				 r->model_before, r->model_after };
	static const char *const key[5] = { "theta_deg", "measured", "sigma",
					    "model_before", "model_after" };
	cJSON *o = cJSON_CreateObject();
	size_t i;
	int k;

	for (k = 0; k < 5; k++) {
		cJSON *a = cJSON_CreateArray();

		for (i = 0; col[k] && i < d->n; i++)
			cJSON_AddItemToArray(a, cli_json_number(col[k][i]));
		cJSON_AddItemToObject(o, key[k], a);
	}
	return o;
}

static cJSON *surfaces_json(const struct diag_surfaces *s, const char *model)
{
	cJSON *o = cJSON_CreateObject(), *list = cJSON_CreateArray();
	int k;

	for (k = 0; k < s->n_named; k++) {
		cJSON *it = cJSON_CreateObject(), *ci = cJSON_CreateArray();
		int c = s->named[k];

		cJSON_AddStringToObject(it, "group", s->name[c]);
		cJSON_AddStringToObject(it, "knob", s->abg[c] ? "abg_a_scale" :
					"reflectance_factor");
		cJSON_AddItemToObject(it, "factor",
				      cli_json_number(pow(10.0, s->log10_f[k])));
		cJSON_AddItemToArray(ci, cli_json_number(pow(10.0, s->ci_lo[k])));
		cJSON_AddItemToArray(ci, cli_json_number(pow(10.0, s->ci_hi[k])));
		cJSON_AddItemToObject(it, "interval", ci);
		cJSON_AddItemToObject(it, "reflectance",
				      cli_json_number(s->rho[c] *
						      pow(10.0, s->log10_f[k])));
		cJSON_AddItemToArray(list, it);
	}
	cJSON_AddItemToObject(o, "groups", list);
	cJSON_AddNumberToObject(o, "candidates", s->n_cand);
	cJSON_AddItemToObject(o, "chi2_before", cli_json_number(s->chi2_before));
	cJSON_AddItemToObject(o, "chi2_after", cli_json_number(s->chi2_after));
	cJSON_AddItemToObject(o, "rms_before", cli_json_number(s->rms_before));
	cJSON_AddItemToObject(o, "rms_after", cli_json_number(s->rms_after));
	cJSON_AddItemToObject(o, "chi2_retrace",
			      cli_json_number(s->chi2_retrace));
	cJSON_AddItemToObject(o, "rms_retrace", cli_json_number(s->rms_retrace));
	cJSON_AddItemToObject(o, "fit_seconds", cli_json_number(s->fit_seconds));
	if (model)
		cJSON_AddStringToObject(o, "model", model);
	return o;
}

int diag_report_json(const struct diag_data *d, const struct diag_eval *e,
		     const struct diag_result *r)
{
	return diag_report_json_surf(d, e, r, NULL, NULL);
}

int diag_report_json_surf(const struct diag_data *d,
			  const struct diag_eval *e,
			  const struct diag_result *r,
			  const struct diag_surfaces *sf, const char *model)
{
	cJSON *o = cJSON_CreateObject(), *single = cJSON_CreateObject();
	cJSON *causes = fit_json(&r->named), *notes = cJSON_CreateArray();
	int i;

	if (r->by_surface && sf)
		surface_causes(causes, sf);
	for (i = 0; i < e->n_notes; i++)
		cJSON_AddItemToArray(notes, cJSON_CreateString(e->notes[i]));
	cJSON_AddStringToObject(o, "scene", e->scene);
	cJSON_AddStringToObject(o, "sensor", r->sensor);
	cJSON_AddBoolToObject(o, "normalised", d->normalised);
	cJSON_AddItemToObject(o, "scene_notes", notes);
	cJSON_AddNumberToObject(o, "n", (double)d->n);
	cJSON_AddBoolToObject(o, "significant", r->significant);
	cJSON_AddBoolToObject(o, "explained", r->explained);
	cJSON_AddItemToObject(o, "causes", causes);
	cJSON_AddItemToObject(o, "interval_delta_chi2",
			      cli_json_number(DIAG_CI_DCHI2));
	cJSON_AddItemToObject(o, "tentative", fit_json(&r->tentative));
	cJSON_AddItemToObject(o, "rms_before", cli_json_number(r->rms_before));
	cJSON_AddItemToObject(o, "rms_after", cli_json_number(r->rms_after));
	cJSON_AddItemToObject(o, "rms_region_before",
			      regions_json(r->rms_region_before, r->n_region));
	cJSON_AddItemToObject(o, "rms_region_after",
			      regions_json(r->rms_region_after, r->n_region));
	cJSON_AddItemToObject(o, "chi2_before", cli_json_number(r->chi2_before));
	cJSON_AddItemToObject(o, "chi2_after", cli_json_number(r->chi2_after));
	cJSON_AddItemToObject(o, "reduced_chi2_before",
			      cli_json_number(r->chi2_before / r->dof_before));
	cJSON_AddItemToObject(o, "reduced_chi2_after", cli_json_number(
		r->dof_after > 0 ? r->chi2_after / r->dof_after : NAN));
	cJSON_AddItemToObject(o, "p_before", cli_json_number(r->p_before));
	cJSON_AddItemToObject(o, "p_after", cli_json_number(r->p_after));
	cJSON_AddItemToObject(o, "worst_theta_deg",
			      cli_json_number(r->worst_theta_deg));
	cJSON_AddItemToObject(o, "worst_pull", cli_json_number(r->worst_pull));
	cJSON_AddItemToObject(o, "sun_alpha_required",
			      cli_json_number(r->sun_alpha_req));
	cJSON_AddItemToObject(o, "sun_deg_before",
			      cli_json_number(r->sun_deg_before));
	cJSON_AddItemToObject(o, "sun_deg_after",
			      cli_json_number(r->sun_deg_after));
	/* the detector of that angle and the failure mode that sets it */
	cJSON_AddStringToObject(o, "detector",
				stray_detector_name(r->detector.kind));
	cJSON_AddStringToObject(o, "sun_binding",
				stray_failure_mode_name(r->detector.binding));
	for (i = 0; i < r->n_single; i++) {
		cJSON *s = cJSON_CreateObject();

		cJSON_AddItemToObject(s, "chi2", cli_json_number(r->single[i].chi2));
		cJSON_AddItemToObject(s, "bic", cli_json_number(r->single[i].bic));
		cJSON_AddItemToObject(single, r->single[i].cause[0]->name, s);
	}
	cJSON_AddItemToObject(o, "single", single);
	if (e->lens)
		cJSON_AddStringToObject(o, "lens", e->lens);
	if (sf)
		cJSON_AddItemToObject(o, "surfaces", surfaces_json(sf, model));
	cJSON_AddItemToObject(o, "curves", curves_json(d, r));
	cJSON_AddNumberToObject(o, "traces", (double)e->n_traces);
	cJSON_AddItemToObject(o, "trace_seconds",
			      cli_json_number(e->trace_seconds));
	return cli_json_emit(o);
}
