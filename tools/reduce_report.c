/*
 * reduce_report.c - the outputs of `stray reduce` other than the curve
 * CSV: Zemax TABLE coating, JSON, text summary.
 */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "reduce_report.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/reduce_map.h"

const char *reduce_track_name(size_t i)
{
	static const char *const names[STRAY_REDUCE_TRACKS_MAX] = {
		"A", "B", "C", "D", "E", "F", "G", "H",
		"I", "J", "K", "L", "M", "N", "O", "P"
	};

	return i < STRAY_REDUCE_TRACKS_MAX ? names[i] : "?";
}

static int coating_name_ok(const char *name)
{
	size_t i, n = strlen(name);

	if (n == 0 || n > 32)
		return 0;
	for (i = 0; i < n; i++)
		if (!isalnum((unsigned char)name[i]) && name[i] != '_')
			return 0;
	return 1;
}

int reduce_write_zemax(const char *path, const char *name, double wave_um,
		       const struct stray_reduce_sweep_result *r, struct stray_error *err)
{
	struct stray_file_out out;
	size_t i;
	int rc;

	if (!coating_name_ok(name)) {
		stray_error_set(err, STRAY_EINVAL, "coating-name",
			"must be 1-32 letters, digits or '_'");
		stray_error_text(err, name);
		return STRAY_EINVAL;
	}
	if ((rc = stray_file_open_atomic(&out, path, err)) != STRAY_OK)
		return rc;
	fprintf(out.f, "! lens attenuation measured by stray reduce "
		"(thesis eq. 3.12); T = alpha_lens, R = 0\n");
	fprintf(out.f, "! append to COATING.DAT after the MATE/COAT entries\n");
	fprintf(out.f, "TABLE %s\n", name);
	for (i = 0; i < r->n_points; i++) {
		const struct stray_curve_point *p = &r->points[i];

		fprintf(out.f, "ANGL %.6g\n", p->theta_deg);
		fprintf(out.f, "WAVE %.6g 0 0 %.10g %.10g\n", wave_um,
			p->alpha, p->alpha);
	}
	return stray_file_commit(&out, err);
}

int reduce_write_map(const char *path, unsigned n_regions,
		     const struct stray_reduce_sweep_result *r, struct stray_error *err)
{
	size_t n = r->n_rows * r->n_cols;
	double *scratch;
	struct stray_region_map map;
	struct stray_file_out out;
	unsigned k;
	int rc;

	if (!r->image)
		return stray_error_set(err, STRAY_ENOTFOUND, "image-angle",
				       "no visit at this angle for the map");
	scratch = malloc(n * sizeof(double));
	if (!scratch)
		return stray_error_set(err, STRAY_ENOMEM, "map", "no memory");
	rc = stray_region_map_from_image(r->image, n, n_regions, scratch, &map,
					 err);
	free(scratch);
	if (rc == STRAY_OK)
		rc = stray_file_open_atomic(&out, path, err);
	if (rc != STRAY_OK)
		return rc;
	fprintf(out.f, "# kind: region map (stray fdr --map)\n"
		"# theta_deg: %.10g\nfraction,rel_alpha\n", r->image_theta_deg);
	for (k = 0; k < map.n; k++)
		fprintf(out.f, "%.10g,%.10g\n", map.fraction[k],
			map.rel_alpha[k]);
	return stray_file_commit(&out, err);
}

static cJSON *track_json(const struct stray_ghost_track *t, size_t i,
			 const struct stray_reduce_sweep_result *r)
{
	cJSON *o = cJSON_CreateObject();
	cJSON *th = cJSON_AddArrayToObject(o, "theta_deg");
	cJSON *col = cJSON_AddArrayToObject(o, "column");
	cJSON *rel = cJSON_AddArrayToObject(o, "rel_power");
	cJSON *al = cJSON_AddArrayToObject(o, "alpha");
	size_t k;

	cJSON_AddStringToObject(o, "name", reduce_track_name(i));
	for (k = 0; k < t->n; k++) {
		const struct stray_ghost_point *p = &t->pt[k];

		cJSON_AddItemToArray(th, cli_json_number(p->theta_deg));
		cJSON_AddItemToArray(col, cli_json_number(p->column +
							  (double)r->col0));
		cJSON_AddItemToArray(rel,
				     cli_json_number(p->excess / p->power));
		cJSON_AddItemToArray(al, cli_json_number(p->excess / r->p0));
	}
	return o;
}

static cJSON *pixels_json(const struct stray_reduce_sweep_result *r, int flag)
{
	cJSON *a = cJSON_CreateArray();
	size_t i;

	for (i = 0; i < r->n_pixlist; i++) {
		cJSON *p;

		if (r->pixlist[i].flag != flag)
			continue;
		p = cJSON_CreateArray();
		cJSON_AddItemToArray(p, cJSON_CreateNumber(r->pixlist[i].row));
		cJSON_AddItemToArray(p, cJSON_CreateNumber(r->pixlist[i].col));
		cJSON_AddItemToArray(a, p);
	}
	return a;
}

static cJSON *curve_json(const struct stray_reduce_sweep_result *r)
{
	cJSON *a = cJSON_CreateArray();
	size_t i;

	for (i = 0; i < r->n_points; i++) {
		const struct stray_curve_point *p = &r->points[i];
		cJSON *o = cJSON_CreateObject();

		cJSON_AddItemToObject(o, "theta_deg",
				      cli_json_number(p->theta_deg));
		cJSON_AddItemToObject(o, "alpha", cli_json_number(p->alpha));
		cJSON_AddItemToObject(o, "sigma", cli_json_number(p->sigma));
		cJSON_AddItemToObject(o, "noise_floor",
				      cli_json_number(p->noise_floor));
		cJSON_AddItemToArray(a, o);
	}
	return a;
}

static cJSON *drift_json(const struct stray_reduce_sweep_result *r)
{
	cJSON *o = cJSON_CreateObject();

	cJSON_AddNumberToObject(o, "on_axis_visits", (double)r->drift.n_ref);
	cJSON_AddBoolToObject(o, "fitted", r->drift.fitted);
	cJSON_AddBoolToObject(o, "detected", r->drift.detected);
	cJSON_AddItemToObject(o, "rel_change",
			      cli_json_number(r->drift.rel_change));
	cJSON_AddItemToObject(o, "z", cli_json_number(r->drift.z));
	cJSON_AddBoolToObject(o, "monitor", r->has_monitor);
	/* against time (date_obs) or, in a folder without it, row order */
	cJSON_AddStringToObject(o, "against", r->drift_in_time ? "time"
							     : "row order");
	if (r->drift_in_time)
		cJSON_AddNumberToObject(o, "span_s", r->span_s);
	return o;
}

cJSON *reduce_json(const struct stray_reduce_sweep_result *r,
		   const char *out_path)
{
	cJSON *o = cJSON_CreateObject();
	cJSON *g = cJSON_AddArrayToObject(o, "ghosts");
	size_t i;

	for (i = 0; i < r->n_tracks; i++)
		cJSON_AddItemToArray(g, track_json(&r->tracks[i], i, r));
	cJSON_AddStringToObject(o, "out", out_path);
	cJSON_AddNumberToObject(o, "frames", (double)r->n_frames);
	cJSON_AddNumberToObject(o, "dark_frames", (double)r->n_darks);
	cJSON_AddNumberToObject(o, "rows", (double)r->n_rows);
	cJSON_AddNumberToObject(o, "columns", (double)r->n_cols);
	cJSON_AddNumberToObject(o, "visits", (double)r->n_visits);
	cJSON_AddItemToObject(o, "curve", curve_json(r));
	/* The normalisation's share of every sigma: their correlation. */
	cJSON_AddItemToObject(o, "p0_rel_sigma",
			      cli_json_number(r->drift.p0_rel_sigma));
	/* Frame-common noise (reduce_common.h), in every sigma. */
	cJSON_AddItemToObject(o, "common_rel_sigma",
			      cli_json_number(r->common_rel_sigma));
	cJSON_AddNumberToObject(o, "hot_pixel_count", (double)r->mask.n_hot);
	cJSON_AddNumberToObject(o, "dead_pixel_count", (double)r->mask.n_dead);
	cJSON_AddItemToObject(o, "hot_pixels", pixels_json(r, STRAY_PIX_HOT));
	cJSON_AddItemToObject(o, "dead_pixels", pixels_json(r, STRAY_PIX_DEAD));
	cJSON_AddNumberToObject(o, "saturated_samples",
				(double)r->n_sat_samples);
	cJSON_AddNumberToObject(o, "saturated_pixels", (double)r->n_sat_pixels);
	cJSON_AddItemToObject(o, "drift", drift_json(r));
	cJSON_AddNumberToObject(o, "workspace_bytes",
				(double)r->workspace_bytes);
	return o;
}

void reduce_print(FILE *out, const struct stray_reduce_sweep_result *r,
		  const char *out_path)
{
	size_t i, k;

	fprintf(out, "sweep: %zu frames (%zu dark), %zu visits, %zu x %zu px\n",
		r->n_frames, r->n_darks, r->n_visits, r->n_rows, r->n_cols);
	fprintf(out, "pixels: %zu hot, %zu dead masked; %lu saturated samples"
		" left out, %zu pixel-visits saturated throughout\n",
		r->mask.n_hot, r->mask.n_dead, r->n_sat_samples,
		r->n_sat_pixels);
	if (r->drift.fitted)
		fprintf(out, "source drift: %+.3g%% over the sweep (%.1f sigma)"
			" from %zu on-axis visits, fitted against %s%s\n",
			100.0 * r->drift.rel_change, r->drift.z, r->drift.n_ref,
			r->drift_in_time ? "time" : "row order (no date_obs)",
			r->drift.detected ? ": DETECTED, corrected" : "");
	fprintf(out, "frame-common noise: %.3g%% per frame (%zu dof), in "
		"every sigma\n", 100.0 * r->common_rel_sigma, r->common_dof);
	fprintf(out, "%10s %14s %12s %12s\n", "theta_deg", "alpha", "sigma",
		"noise_floor");
	for (i = 0; i < r->n_points; i++)
		fprintf(out, "%10.4g %14.6g %12.3g %12.3g\n",
			r->points[i].theta_deg, r->points[i].alpha,
			r->points[i].sigma, r->points[i].noise_floor);
	for (i = 0; i < r->n_tracks; i++) {
		const struct stray_ghost_track *t = &r->tracks[i];

		fprintf(out, "ghost %s: %zu angles, %.4g..%.4g deg:",
			reduce_track_name(i), t->n, t->pt[0].theta_deg,
			t->pt[t->n - 1].theta_deg);
		for (k = 0; k < t->n; k++)
			fprintf(out, " %.4g@%.1f(%.2g)", t->pt[k].theta_deg,
				t->pt[k].column + (double)r->col0,
				t->pt[k].excess / t->pt[k].power);
		fprintf(out, "\n");
	}
	fprintf(out, "wrote %s\n", out_path);
}
