/*
 * fdr_setup.c - what the commands that answer with the FDR model share
 * (stray/fdr_setup.h): the sensor, its spectra and the model's
 * extensions turned into fluxes, an FDR model and a detector.  Their
 * command-line options are tools/fdr_options.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/fdr_setup.h"
#include "stray/errfmt.h"
#include "stray/photometry.h"
#include "stray/sensor_io.h"
#include "stray/table.h"

void fdr_setup_init(struct fdr_setup *s)
{
	memset(s, 0, sizeof(*s));
	s->sensor_spec = "st16-like";
	s->rate = NAN;
	s->earth_albedo = 0.3;
	s->altitude_km = 550.0;
	s->detector_sigma = NAN;
}

/* A region map from a CSV with columns fraction,rel_alpha. */
static int load_map(const char *path, struct stray_region_map *map,
		    struct stray_error *err)
{
	struct stray_table t;
	int cf, ca, rc = stray_table_read(path, &t, err), lit = 0;
	size_t i;

	if (rc != STRAY_OK)
		return rc;
	cf = stray_table_find(&t, "fraction");
	ca = stray_table_find(&t, "rel_alpha");
	if (cf < 0 || ca < 0)
		rc = stray_error_at(err, STRAY_EPARSE, path, 0,
				    cf < 0 ? "fraction" : "rel_alpha",
				    "required column is missing");
	else if (t.n_rows < 1 || t.n_rows > STRAY_MAP_REGIONS_MAX)
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "rows",
				    "a map needs 1 to 64 regions");
	for (i = 0; rc == STRAY_OK && i < t.n_rows; i++) {
		map->fraction[i] = t.cell[i * t.n_cols + (size_t)cf];
		map->rel_alpha[i] = t.cell[i * t.n_cols + (size_t)ca];
		lit |= map->rel_alpha[i] > 0.0 && map->fraction[i] > 0.0;
	}
	if (rc == STRAY_OK && !lit)	/* the mean of rel_alpha is 1 */
		rc = stray_error_at(err, STRAY_EPARSE, path, 0, "rel_alpha",
			"every region is dark (all rel_alpha 0): a map "
			"normalised to mean 1 has some light");
	map->n = (unsigned)t.n_rows;
	stray_table_free(&t);
	return rc;
}

int fdr_setup_load(struct fdr_setup *s, struct stray_error *err)
{
	struct stray_fdr_model m;
	int rc = stray_sensor_load(s->sensor_spec, &s->sensor, err);

	if (rc != STRAY_OK)
		return rc;
	if (s->sun)
		snprintf(s->sensor.sun, sizeof(s->sensor.sun), "%s", s->sun);
	if (s->vega)
		snprintf(s->sensor.vega, sizeof(s->sensor.vega), "%s", s->vega);
	if (s->qe)
		snprintf(s->sensor.qe, sizeof(s->sensor.qe), "%s", s->qe);
	if (isnan(s->rate))
		s->rate = s->sensor.fdr_tolerated;
	/* the command line's detector, else the sensor file's, else thesis */
	s->detector = STRAY_DET_THESIS;
	if (s->detector_name)
		stray_detector_parse(s->detector_name, &s->detector, NULL);
	else if (s->sensor.detector[0])
		stray_detector_parse(s->sensor.detector, &s->detector, NULL);
	if (isnan(s->detector_sigma))
		s->detector_sigma = s->sensor.detector_sigma > 0.0 ?
			s->sensor.detector_sigma : 3.0;
	rc = stray_reference_fluxes(&s->sensor, &s->flux, err);
	if (rc == STRAY_OK && s->map_path)
		rc = load_map(s->map_path, &s->map, err);
	if (rc != STRAY_OK)
		return rc;
	/* Validate the whole model once, so errors name the bad field. */
	fdr_setup_model(s, s->flux.sun, &m);
	rc = stray_fdr_model_check(&m, err);
	if (rc != STRAY_OK && s->map_path)
		stray_error_locate(err, s->map_path, 0);
	return rc;
}

void fdr_setup_model(const struct fdr_setup *s, double f_src,
		     struct stray_fdr_model *m)
{
	stray_sensor_fdr_model(&s->sensor, f_src, s->flux.drs, m);
	m->k_px = fdr_setup_k_px(s);
	/* The real detectors' models are validated with the camera's read
	 * noise and dark current (docs/detectors.md): always on for them. */
	if (s->detector_noise || s->detector != STRAY_DET_THESIS) {
		m->read_noise_e = s->sensor.read_noise_e;
		m->dark_current_e_s = s->sensor.dark_current_e_s;
	}
	m->noise = s->poisson ? STRAY_NOISE_POISSON : STRAY_NOISE_GAUSS;
	m->map = s->map_path ? &s->map : NULL;
}

/* The sensor came from a file (its numbers are the user's to fix). */
static int sensor_is_file(const struct fdr_setup *s)
{
	return strchr(s->sensor_spec, '/') || strstr(s->sensor_spec, ".json");
}

int fdr_setup_detector(const struct fdr_setup *s,
		       const struct stray_fdr_model *m, struct stray_detector *d,
		       struct stray_error *err)
{
	int rc;

	stray_detector_init(d, s->detector, s->sensor.star_window_px);
	d->sigma_k = s->detector_sigma;
	rc = stray_detector_setup(d, m, err);
	/* what the detector refuses comes from the sensor's numbers */
	if (rc != STRAY_OK && sensor_is_file(s))
		stray_error_locate(err, s->sensor_spec, 0);
	return rc;
}

int fdr_setup_alpha_required(const struct fdr_setup *s,
			     const struct stray_fdr_model *m,
			     struct stray_detector_req *r,
			     struct stray_error *err)
{
	struct stray_detector d;
	int rc = fdr_setup_detector(s, m, &d, err);

	if (rc != STRAY_OK)
		return rc;
	if (s->detector == STRAY_DET_THESIS) {
		/* eq. 2.18 as published, exactly as before detectors */
		r->alpha_lost = NAN;
		r->binding = STRAY_FAIL_FALSE_STARS;
		rc = stray_fdr_alpha_required(m, s->rate, &r->alpha_false, err);
		r->alpha_req = r->alpha_false;
		return rc;
	}
	rc = stray_detector_alpha_required(&d, m, s->rate, s->sensor.pr_drs, r,
					   err);
	if (rc != STRAY_OK && sensor_is_file(s))
		stray_error_locate(err, s->sensor_spec, 0);
	return rc;
}

double fdr_setup_k_px(const struct fdr_setup *s)
{
	return stray_sensor_k_px(&s->sensor, s->normalisation);
}

double fdr_setup_moon_flux(const struct fdr_setup *s)
{
	return stray_mag_to_flux(s->flux.zero_mag,
		stray_moon_mag_at_phase(s->sensor.moon_mag, s->moon_phase_deg));
}

int fdr_setup_earth_flux(const struct fdr_setup *s, double *flux,
			 struct stray_error *err)
{
	return stray_earth_flux(s->flux.sun, s->earth_albedo,
				s->altitude_km * 1e3, flux, err);
}
