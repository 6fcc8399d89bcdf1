/*
 * report_steps.c - the design section of a review (the drawing of the
 * scene's section, the scene's own keys and coatings, the sensor, the
 * lens) and one section per step of the manifest, in its order.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "review_int.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sensor_io.h"

static void sensor_table(struct review_doc *d, const struct review_project *p)
{
	static const char *const head[3] = { "sensor key", "value", "unit" };
	struct stray_sensor s;
	struct stray_error e;
	char v[14][64];
	const char *rows[14][3] = {
		{ "name", v[0], "" }, { "pixels_x", v[1], "px" },
		{ "pixels_y", v[2], "px" }, { "pixel_pitch_um", v[3], "um" },
		{ "t_exp_s", v[4], "s" }, { "aperture_diameter_mm", v[5], "mm" },
		{ "star_window_px", v[6], "px" }, { "drs_mag", v[7], "mag" },
		{ "fdr_tolerated", v[8], "false stars per image" },
		{ "fov_half_deg", v[9], "deg" }, { "read_noise_e", v[10], "e- rms" },
		{ "dark_current_e_s", v[11], "e-/s" }, { "qe", v[12], "" },
		{ "sun", v[13], "" } };
	int i;

	if (stray_sensor_load(p->sensor, &s, &e) != STRAY_OK) {
		doc_p(d, "Sensor %s: could not be read.", p->sensor);
		return;
	}
	snprintf(v[0], 64, "%s", s.name);
	snprintf(v[1], 64, "%g", s.pixels_x);
	snprintf(v[2], 64, "%g", s.pixels_y);
	snprintf(v[3], 64, "%g", s.pixel_pitch_um);
	snprintf(v[4], 64, "%g", s.t_exp_s);
	snprintf(v[5], 64, "%g", s.aperture_diameter_mm);
	snprintf(v[6], 64, "%g", s.star_window_px);
	snprintf(v[7], 64, "%g", s.drs_mag);
	snprintf(v[8], 64, "%g", s.fdr_tolerated);
	snprintf(v[9], 64, "%g", s.fov_half_deg);
	snprintf(v[10], 64, "%g", s.read_noise_e);
	snprintf(v[11], 64, "%g", s.dark_current_e_s);
	snprintf(v[12], 64, "%.63s", strrchr(s.qe, '/') ? strrchr(s.qe, '/') + 1 : s.qe);
	snprintf(v[13], 64, "%.63s", strrchr(s.sun, '/') ? strrchr(s.sun, '/') + 1 : s.sun);
	doc_p(d, "Sensor %s (%s):", s.name, p->sensor);
	doc_table(d, 3, head);
	for (i = 0; i < 14; i++)
		doc_row(d, 3, rows[i]);
	doc_table_end(d);
}

void review_design(struct review_doc *d, const char *dir,
		   const struct review_project *p,
		   const struct review_plan *plan)
{
	static const char *const head[2] = { "override (--set)", "value" };
	char key[96], *eq, *text = NULL;
	const char *cells[2];
	struct stray_error e;
	size_t len;
	cJSON *scene;
	int i;

	doc_h2(d, "Design", "design");
	if (review_step_done(plan, "trace") && exists_file(dir, "design.png"))
		doc_fig(d, "design.png", "section of the traced scene through its axis (x-z plane, mm)");
	if (strchr(p->scene, '/') && stray_file_read(p->scene, &text, &len, &e) == STRAY_OK &&
	    (scene = cJSON_ParseWithLength(text, len))) {
		doc_p(d, "Scene file %s, as written (coatings are its reflectance and materials keys):",
		      p->scene);
		review_json_tables(d, scene, "scene", NULL);
		cJSON_Delete(scene);
	} else {
		doc_p(d, "Scene: the built-in %s; its parameters: stray trace --help.", p->scene);
	}
	free(text);
	if (p->n_set) {
		doc_table(d, 2, head);
		for (i = 0; i < p->n_set; i++) {
			snprintf(key, sizeof(key), "%s", p->set[i]);
			eq = strchr(key, '=');
			*eq = '\0';
			cells[0] = key;
			cells[1] = eq + 1;
			doc_row(d, 2, cells);
		}
		doc_table_end(d);
	} else {
		doc_p(d, "No --set overrides: the scene as written.");
	}
	sensor_table(d, p);
	switch (p->lens) {
	case REVIEW_LENS_NONE: doc_p(d, "Lens: none named; the baffle alone is traced."); break;
	case REVIEW_LENS_IDEAL: doc_p(d, "Lens: ideal (cos^4 inside the field, 0 beyond)."); break;
	case REVIEW_LENS_CSV: doc_p(d, "Lens: the curve %s.", p->lens_path); break;
	case REVIEW_LENS_SWEEP: doc_p(d, "Lens: reduced from the lab sweep %s.", p->lens_path); break;
	}
	doc_end_section(d);
}

static void exclusion_lines(struct review_doc *d, const cJSON *j)
{
	static const char *const body[3] = { "sun", "moon", "earth" };
	const cJSON *det = cJSON_GetObjectItemCaseSensitive(j, "detector");
	int b;

	/* the thesis's text as it was; a named detector says which failure
	 * mode sets each angle (issue 28) */
	if (cJSON_IsString(det) && strcmp(det->valuestring, "thesis") != 0)
		doc_p(d, "Detector %s: alpha_required is where its false stars "
		      "stay within the rate and the reference star stays "
		      "detected (docs/detectors.md).", det->valuestring);

	for (b = 0; b < 3; b++) {
		const cJSON *o = cJSON_GetObjectItemCaseSensitive(j, body[b]);
		const cJSON *deg = cJSON_GetObjectItemCaseSensitive(o, "curve_deg");
		const cJSON *lo = cJSON_GetObjectItemCaseSensitive(o, "deg_lo");
		const cJSON *hi = cJSON_GetObjectItemCaseSensitive(o, "deg_hi");
		const cJSON *why = cJSON_GetObjectItemCaseSensitive(o, "reason");
		const cJSON *ar = cJSON_GetObjectItemCaseSensitive(o, "alpha_required");

		if (!o)
			continue;
		if (cJSON_IsNumber(deg) && cJSON_IsString(det) &&
		    strcmp(det->valuestring, "thesis") != 0)
			doc_p(d, "%s: excluded beyond %.2f deg [%.2f, %.2f] deg, where alpha falls under alpha_required = %.3g (%s bind).",
			      body[b], deg->valuedouble,
			      cJSON_IsNumber(lo) ? lo->valuedouble : NAN,
			      cJSON_IsNumber(hi) ? hi->valuedouble : NAN,
			      cJSON_IsNumber(ar) ? ar->valuedouble : NAN,
			      cJSON_IsString(cJSON_GetObjectItemCaseSensitive(
				o, "binding")) ? cJSON_GetObjectItemCaseSensitive(
				o, "binding")->valuestring : "?");
		else if (cJSON_IsNumber(deg))
			doc_p(d, "%s: excluded beyond %.2f deg [%.2f, %.2f] deg, where alpha falls under alpha_required = %.3g.",
			      body[b], deg->valuedouble,
			      cJSON_IsNumber(lo) ? lo->valuedouble : NAN,
			      cJSON_IsNumber(hi) ? hi->valuedouble : NAN,
			      cJSON_IsNumber(ar) ? ar->valuedouble : NAN);
		else
			doc_p(d, "%s: not excluded: %s.", body[b],
			      cJSON_IsString(why) ? why->valuestring : "no reason given");
	}
}

static void diagnose_causes(struct review_doc *d, const cJSON *j)
{
	static const char *const head[5] = { "cause", "side", "parameter",
					     "found (interval)", "scene nominal" };
	const cJSON *c, *k, *sig = cJSON_GetObjectItemCaseSensitive(j, "significant");
	char val[128], nom[64];
	const char *cells[5];
	int rows = 0;

	doc_p(d, "Discrepancy with the model significant: %s.",
	      cJSON_IsTrue(sig) ? "yes" : "no");
	cJSON_ArrayForEach(c, cJSON_GetObjectItemCaseSensitive(j, "causes")) {
		cJSON_ArrayForEach(k, cJSON_GetObjectItemCaseSensitive(c, "params")) {
			const cJSON *iv = cJSON_GetObjectItemCaseSensitive(
				cJSON_GetObjectItemCaseSensitive(c, "intervals"), k->string);
			const cJSON *n = cJSON_GetObjectItemCaseSensitive(
				cJSON_GetObjectItemCaseSensitive(c, "nominal"), k->string);

			if (!rows++)
				doc_table(d, 5, head);
			if (cJSON_GetArraySize(iv) == 2)
				snprintf(val, sizeof(val), "%.4g [%.4g, %.4g] %s", k->valuedouble,
					 cJSON_GetArrayItem(iv, 0)->valuedouble,
					 cJSON_GetArrayItem(iv, 1)->valuedouble, review_unit(k->string));
			else
				snprintf(val, sizeof(val), "%.4g %s", k->valuedouble,
					 review_unit(k->string));
			if (cJSON_IsNumber(n))
				snprintf(nom, sizeof(nom), "%.4g", n->valuedouble);
			else
				snprintf(nom, sizeof(nom), "-");
			cells[0] = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(c, "name"));
			cells[1] = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(c, "side"));
			cells[2] = k->string;
			cells[3] = val;
			cells[4] = nom;
			doc_row(d, 5, cells);
		}
	}
	if (rows)
		doc_table_end(d);
	else
		doc_p(d, "No cause named.");
}

static void mission_lines(struct review_doc *d, const struct review_project *p)
{
	if (p->ltan[0])
		doc_p(d, "Orbit: circular, %.0f km, sun-synchronous with the ascending node at %s local time; from %s 00:00 UTC for %g h, a record every %g s; attitude %s.",
		      p->altitude_km, p->ltan, p->epoch, p->hours, p->step_s, p->attitude);
	else
		doc_p(d, "Orbit: circular, %.0f km, inclination %g deg; from %s 00:00 UTC for %g h, a record every %g s; attitude %s.",
		      p->altitude_km, p->incl_deg, p->epoch, p->hours, p->step_s, p->attitude);
}

static void step_body(struct review_doc *d, const char *dir,
		      const struct review_project *p, const struct review_step *s)
{
	static const char *const skip_diag[] = { "causes", "tentative", "scene_notes",
						 "surfaces", NULL };
	cJSON *j = s->stdout_file[0] ? review_read_json(dir, s->stdout_file) : NULL;
	int k;

	if (strcmp(s->name, "exclusion") == 0 && j)
		exclusion_lines(d, j);
	if (strcmp(s->name, "diagnose") == 0 && j)
		diagnose_causes(d, j);
	if (strcmp(s->name, "mission") == 0)
		mission_lines(d, p);
	if (strcmp(s->name, "fdr_at_requirement") == 0 && j) {
		const cJSON *a = cJSON_GetObjectItemCaseSensitive(j, "alpha");
		const cJSON *f = cJSON_GetObjectItemCaseSensitive(j, "fdr");
		double th = 0.0;
		int i;

		for (i = 0; i < p->n_req; i++)
			if (strcmp(p->req[i].key, "sun_exclusion_deg_max") == 0)
				th = p->req[i].value;
		if (cJSON_IsNumber(a) && cJSON_IsNumber(f) && a->valuedouble <= 1e-29)
			doc_p(d, "At and beyond the required Sun angle, %g deg, the system curve is 0 (the trace found no path): 0 false stars per image.",
			      th);
		else if (cJSON_IsNumber(a) && cJSON_IsNumber(f))
			doc_p(d, "At and beyond the required Sun angle, %g deg, the system's largest attenuation is %.3g: %.3g false stars per image with the Sun there.",
			      th, a->valuedouble, f->valuedouble);
	}
	if (j)
		review_json_tables(d, j, "", strcmp(s->name, "diagnose") == 0 ?
				   skip_diag : NULL);
	cJSON_Delete(j);
	for (k = 0; k < s->n_outs; k++) {
		size_t n = strlen(s->outs[k]);

		if (n > 4 && strcmp(s->outs[k] + n - 4, ".png") == 0 &&
		    exists_file(dir, s->outs[k]))
			doc_fig(d, s->outs[k], s->outs[k]);
	}
}

void review_step_sections(struct review_doc *d, const char *dir,
			  const struct review_project *p,
			  const struct review_plan *plan)
{
	char cmd[4096], id[64];
	size_t n;
	int i, k;

	for (i = 0; i < plan->n; i++) {
		const struct review_step *s = &plan->step[i];
		int done = s->status && strcmp(s->status, "done") == 0;

		snprintf(id, sizeof(id), "step-%s", s->name);
		doc_h2(d, s->title, id);
		if (!done) {
			doc_p(d, "Step %s %s: %s.", s->name,
			      s->status && strcmp(s->status, "failed") == 0 ? "failed" : "not run",
			      s->why ? s->why : "no reason recorded");
			doc_end_section(d);
			continue;
		}
		for (n = 0, k = 0; k < s->argc && n < sizeof(cmd); k++)
			n += (size_t)snprintf(cmd + n, sizeof(cmd) - n, "%s%s",
					      k ? " " : "", s->argv[k]);
		doc_p(d, "Step %s, done in %.1f s: %s%s%s", s->name, s->seconds, cmd,
		      s->stdout_file[0] ? " > " : "", s->stdout_file);
		step_body(d, dir, p, s);
		doc_end_section(d);
	}
}
