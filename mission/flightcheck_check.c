/*
 * flightcheck_check.c - `stray flightcheck` as one call (flightcheck_check.h):
 * the model curve, the head's AEM, the catalogue and its colour term and
 * the orbit loaded; every flight frame analysed (flightcheck_run.c); the
 * model at each frame's angle; the calibration, the scale and the
 * verdict (flightcheck.c); and the flight curve written for diagnose.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mission/flightcheck_check.h"
#include "stray/colour.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/starcat.h"

/* The catalogue (and its colour term through the sensor's QE), its name
 * for the outputs: "synthetic" without one. */
static int load_catalogue(const struct fc_check_opts *o,
			  const struct fdr_setup *su, struct stray_starcat *cat,
			  struct stray_colour *colour, char *name, size_t size,
			  struct stray_error *err)
{
	const char *base;
	int rc;

	snprintf(name, size, "synthetic");
	if (!o->catalogue)
		return STRAY_OK;
	base = strrchr(o->catalogue, '/');
	if ((rc = stray_starcat_load(o->catalogue, cat, err)) == STRAY_OK &&
	    (rc = stray_colour_for_qe(colour, su->sensor.qe, err)) != STRAY_OK)
		stray_starcat_free(cat);
	if (rc != STRAY_OK)
		return rc;
	snprintf(name, size, "%s %.50s", stray_starcat_kind_name(cat->kind),
		 base ? base + 1 : o->catalogue);
	return STRAY_OK;
}

/* Every frame analysed under the sky of o (catalogue, orbit, screens). */
static int run_frames(const struct fc_check_opts *o,
		      const struct fdr_setup *su, struct fc_check *c,
		      struct stray_error *err)
{
	struct fc_sky sky = { 0 };
	struct stray_starcat cat;
	struct stray_colour colour;
	struct stray_aem aem;
	struct stray_oem oem;
	int rc;

	if ((rc = stray_aem_read(o->aem, &aem, err)) != STRAY_OK)
		return rc;
	rc = load_catalogue(o, su, &cat, &colour, c->cat_name,
			    sizeof(c->cat_name), err);
	if (rc != STRAY_OK) {
		stray_aem_free(&aem);
		return rc;
	}
	if (o->oem && (rc = stray_oem_read(o->oem, &oem, err)) != STRAY_OK) {
		if (o->catalogue)
			stray_starcat_free(&cat);
		stray_aem_free(&aem);
		return rc;
	}
	sky.cat = o->catalogue ? &cat : NULL;
	sky.colour = o->catalogue ? &colour : NULL;
	sky.oem = o->oem ? &oem : NULL;
	sky.moon_min_deg = o->moon_min_deg;
	sky.limb_min_deg = o->limb_min_deg;
	sky.files = o->files;
	sky.n_files = o->n_files;
	rc = fc_run_dir_sky(o->dir, &aem, &su->sensor, &su->flux, &sky,
			    &c->cfg, &c->f, &c->n, err);
	if (o->catalogue)
		stray_starcat_free(&cat);
	if (o->oem)
		stray_oem_free(&oem);
	stray_aem_free(&aem);
	return rc;
}

int fc_check_run(const struct fc_check_opts *o, const struct fdr_setup *su,
		 struct fc_check *c, struct stray_error *err)
{
	struct stray_curve model;
	struct stray_curve_view mv;
	size_t i;
	int rc;

	memset(c, 0, sizeof(*c));
	if ((rc = stray_curve_load(o->model, &model, err)) != STRAY_OK)
		return rc;
	if ((rc = run_frames(o, su, c, err)) != STRAY_OK) {
		stray_curve_free(&model);
		return rc;
	}
	mv = stray_curve_view_of(&model);
	c->p = calloc(c->n, sizeof(*c->p));
	for (i = 0; c->p && i < c->n; i++)
		c->p[i].model = stray_curve_alpha_at(&mv, c->f[i].theta_deg);
	stray_curve_free(&model);
	if (!c->p) {
		fc_check_free(c);
		return stray_error_set(err, STRAY_ENOMEM, "flightcheck",
				       "out of memory");
	}
	fc_summarise(&c->cfg, c->f, c->n, fdr_setup_k_px(su), c->p, &c->s);
	fc_verdict(&c->s, c->why, sizeof(c->why));
	return STRAY_OK;
}

void fc_check_free(struct fc_check *c)
{
	free(c->f);
	free(c->p);
	c->f = NULL;
	c->p = NULL;
}

int fc_write_curve(const char *path, const struct fc_point *p, size_t n,
		   const struct fc_summary *s, const char *cat_name,
		   struct stray_error *err)
{
	struct stray_curve c;
	double *model = malloc(n * sizeof(*model));
	size_t i;
	char v[64];
	int rc;

	if (!model)
		return stray_error_set(err, STRAY_ENOMEM, "out", "out of memory");
	if ((rc = stray_curve_alloc(&c, n, 1, err)) != STRAY_OK) {
		free(model);
		return rc;
	}
	for (i = 0; i < n; i++) {
		c.theta_deg[i] = p[i].theta_deg;
		c.alpha[i] = p[i].alpha_px / s->k_px_model;
		c.sigma[i] = p[i].sigma / s->k_px_model;
		model[i] = p[i].model;
	}
	snprintf(v, sizeof(v), "%.6g", s->scale_over_kpx);
	rc = stray_curve_add_column(&c, "model", model, err);
	if (!rc)
		rc = stray_curve_add_meta(&c, "kind", "flight (stray flightcheck)", err);
	if (!rc)
		rc = stray_curve_add_meta(&c, "scale_over_k_px", v, err);
	if (!rc)
		rc = stray_curve_add_meta(&c, "stars", cat_name, err);
	/* sigma is the background's; the star calibration is one factor
	 * common to every point: add it to any fitted scale */
	snprintf(v, sizeof(v), "%.4g", s->dn_per_e_sigma / s->dn_per_e);
	if (!rc)
		rc = stray_curve_add_meta(&c, "calibration_rel_sigma", v, err);
	if (!rc)
		rc = stray_curve_save(path, &c, err);
	stray_curve_free(&c);
	free(model);
	return rc;
}
