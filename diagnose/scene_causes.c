/*
 * scene_causes.c - the registry fitted to the scene a diagnosis runs on
 * (issue 23).  A cause's nominal value is the scene's own (its interior
 * reflectance from the nominal trace, its knife-edge radius), not the
 * built-in baffle's: a 5 % scene is not reported against "nominal 0.04".
 * A re-trace cause keeps only the grid nodes the scene can be built with
 * (a 0.3 mm fillet does not fit on a 0.5 mm vane's 45 deg bevel): the
 * others are skipped and said in e->notes, never the end of the run, and
 * the fit is bounded by the last node kept.  `--causes` / `--without`
 * choose which causes run.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>

#include "diagnose/diag_eval.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "trace_scene.h"

/* name in a comma list */
static int listed(const char *list, const char *name)
{
	size_t n = strlen(name);
	const char *p = list;

	while (p && *p) {
		const char *end = strchr(p, ',');
		size_t len = end ? (size_t)(end - p) : strlen(p);

		if (len == n && strncmp(p, name, n) == 0)
			return 1;
		p = end ? end + 1 : NULL;
	}
	return 0;
}

const char *diag_causes_check(const char *list, char *bad, size_t n)
{
	const char *p = list;

	while (p && *p) {
		const char *end = strchr(p, ',');
		size_t len = end ? (size_t)(end - p) : strlen(p);
		int i, found = 0;

		for (i = 0; diag_causes[i]; i++)
			found |= strlen(diag_causes[i]->name) == len &&
				 strncmp(p, diag_causes[i]->name, len) == 0;
		if (!found) {
			snprintf(bad, n, "%.*s", (int)(len < 100 ? len : 100), p);
			return bad;
		}
		p = end ? end + 1 : NULL;
	}
	return NULL;
}

static void note(struct diag_eval *e, const char *fmt, const char *cause,
		 double v, const char *why)
{
	if (e->n_notes < DIAG_NOTES_MAX)
		snprintf(e->notes[e->n_notes++], sizeof(e->notes[0]), fmt,
			 cause, v, why);
}

/* The scene's knife-edge radius: the last --set, else the vane file's
 * key, else 0 (ref4, a mesh as given). */
static double scene_edge_radius(const struct diag_eval *e)
{
	double v = 0.0;
	int i;

	for (i = 0; i < e->n_sets; i++)
		if (strncmp(e->sets[i], "edge_radius=", 12) == 0)
			return strtod(e->sets[i] + 12, NULL);
	if (e->parametric && strcmp(e->scene, "ref4") != 0) {
		struct stray_error err;
		size_t len;
		char *text = NULL;
		cJSON *root, *r;

		stray_error_clear(&err);
		if (stray_file_read(e->scene, &text, &len, &err) != STRAY_OK)
			return 0.0;
		root = cJSON_Parse(text);
		r = cJSON_GetObjectItemCaseSensitive(root, "edge_radius");
		if (cJSON_IsNumber(r) && isfinite(r->valuedouble))
			v = r->valuedouble;
		cJSON_Delete(root);
		free(text);
	}
	return v;
}

/* The nodes of a re-trace cause the scene can be built with; 0 when
 * fewer than two are left (nothing to interpolate: the cause is left
 * out). */
static int keep_nodes(struct diag_eval *e, struct diag_cause *c,
		       double *own)
{
	double geo[DIAG_GEO_N];
	int k, n = 0, a;

	for (k = 0; k < c->n_nodes && n < DIAG_NODES_MAX; k++) {
		struct stray_error err;

		for (a = 0; a < DIAG_GEO_N; a++)
			geo[a] = NAN;
		geo[c->geo_axis] = c->nodes[k];
		stray_error_clear(&err);
		/* meshes: only the fillet can fail (its import is costly) */
		if ((e->parametric || c->geo_axis == DIAG_GEO_EDGE_RADIUS) &&
		    diag_geometry_check(e, geo, &err) != STRAY_OK) {
			char line[160];

			stray_error_format(&err, line, sizeof(line));
			note(e, "%s: grid point %g skipped (%s)", c->name,
			     c->nodes[k], line);
			continue;
		}
		own[n++] = c->nodes[k];
	}
	c->nodes = own;
	c->n_nodes = n;
	if (c->n_params > 0 && n > 0 && own[n - 1] < c->param[0].hi) {
		c->param[0].hi = own[n - 1];
		note(e, "%s: fitted up to %g, the largest grid point this "
		     "scene can be built with%s", c->name, own[n - 1], "");
	}
	return n >= 2;
}

int diag_eval_causes(struct diag_eval *e, double base_rho,
		     struct stray_error *err)
{
	int i, n = 0;

	(void)err;
	e->n_notes = 0;
	for (i = 0; diag_causes[i] && n < DIAG_CAUSES_MAX; i++) {
		struct diag_cause *c = &e->cause_own[n];

		if ((e->only && !listed(e->only, diag_causes[i]->name)) ||
		    (e->without && listed(e->without, diag_causes[i]->name)))
			continue;
		*c = *diag_causes[i];
		/* the scene's own coating: reflectance, spectral_slope's rho0 */
		if (c->kind == DIAG_REWEIGHT && c->n_params > 0 &&
		    strcmp(c->param[0].name, "reflectance") == 0 &&
		    isfinite(base_rho) && base_rho > 0.0) {
			c->param[0].nominal = base_rho;
			if (c->param[0].hi < 2.0 * base_rho)
				c->param[0].hi = fmin(2.0 * base_rho, 1.0);
		}
		if (c->kind == DIAG_RETRACE &&
		    c->geo_axis == DIAG_GEO_EDGE_RADIUS)
			c->param[0].nominal = scene_edge_radius(e);
		if (c->kind == DIAG_RETRACE && c->nodes &&
		    !keep_nodes(e, c, e->node_own[n])) {
			note(e, "%s: dropped (%g grid points left: %s)",
			     c->name, (double)c->n_nodes,
			     "the scene cannot be built at the others");
			continue;
		}
		e->causes[n++] = c;
	}
	e->causes[n] = NULL;
	return STRAY_OK;
}

const struct diag_cause *diag_eval_axis_cause(const struct diag_eval *e,
					      int axis)
{
	const struct diag_cause *const *list =
		e->causes[0] ? e->causes : diag_causes;
	int i;

	for (i = 0; list[i]; i++)
		if (list[i]->kind == DIAG_RETRACE && list[i]->geo_axis == axis)
			return list[i];
	/* a cause left out by --without still names its axis's nodes */
	for (i = 0; diag_causes[i]; i++)
		if (diag_causes[i]->kind == DIAG_RETRACE &&
		    diag_causes[i]->geo_axis == axis)
			return diag_causes[i];
	return NULL;
}
