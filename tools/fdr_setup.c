/*
 * fdr_setup.c - shared sensor/model options of `stray fdr` and
 * `stray exclusion`.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fdr_setup.h"
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

int fdr_setup_option(struct fdr_setup *s, const char *cmd, int opt,
		     const char *arg)
{
	switch (opt) {
	case 1000: s->sensor_spec = arg; return 1;
	case 1001: s->sun = arg; return 1;
	case 1002: s->vega = arg; return 1;
	case 1003: s->qe = arg; return 1;
	case 1004:
		if (strcmp(arg, "gauss") != 0 && strcmp(arg, "poisson") != 0)
			return cli_usage_error(cmd,
				"option '--noise': '%s' is not gauss or poisson", arg);
		s->poisson = strcmp(arg, "poisson") == 0;
		return 1;
	case 1005: s->detector_noise = 1; return 1;
	case 1006: s->map_path = arg; return 1;
	case 1007:
		if (cli_parse_double(cmd, "moon-phase", arg, &s->moon_phase_deg))
			return CLI_USAGE;
		if (s->moon_phase_deg < 0.0 || s->moon_phase_deg > 180.0)
			return cli_usage_error(cmd,
				"option '--moon-phase': %g is outside 0..180 deg",
				s->moon_phase_deg);
		return 1;
	case 1008:
		return cli_parse_double(cmd, "rate", arg, &s->rate) ? CLI_USAGE : 1;
	case 1009:
		s->earth_given = 1;
		return cli_parse_double(cmd, "earth-albedo", arg,
					&s->earth_albedo) ? CLI_USAGE : 1;
	case 1010:
		return cli_parse_double(cmd, "altitude-km", arg,
					&s->altitude_km) ? CLI_USAGE : 1;
	case 1011:
		if (strcmp(arg, "consistent") != 0 && strcmp(arg, "thesis") != 0)
			return cli_usage_error(cmd,
				"option '--normalisation': '%s' is not consistent or thesis",
				arg);
		s->normalisation = strcmp(arg, "thesis") == 0 ?
			STRAY_NORM_THESIS : STRAY_NORM_CONSISTENT;
		return 1;
	case 1012: {
		enum stray_detector_kind k;

		if (stray_detector_parse(arg, &k, NULL) != STRAY_OK)
			return cli_usage_error(cmd,
				"option '--detector': '%s' is not thesis, window, threshold or tetra3",
				arg);
		s->detector_name = arg;
		return 1;
	}
	case 1013:
		if (cli_parse_double(cmd, "detector-sigma", arg,
				     &s->detector_sigma))
			return CLI_USAGE;
		if (!(s->detector_sigma >= 0.5 && s->detector_sigma <= 20.0))
			return cli_usage_error(cmd,
				"option '--detector-sigma': %g is outside 0.5..20",
				s->detector_sigma);
		return 1;
	default:
		return 0;
	}
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

void fdr_setup_detector_json(const struct fdr_setup *s, cJSON *o)
{
	cJSON_AddStringToObject(o, "detector", stray_detector_name(s->detector));
	if (s->detector == STRAY_DET_TETRA3)
		cJSON_AddItemToObject(o, "detector_sigma",
				      cli_json_number(s->detector_sigma));
}

double fdr_setup_k_px(const struct fdr_setup *s)
{
	return stray_sensor_k_px(&s->sensor, s->normalisation);
}

void fdr_setup_json(const struct fdr_setup *s, cJSON *o)
{
	cJSON_AddStringToObject(o, "normalisation",
				stray_normalisation_name(s->normalisation));
	cJSON_AddItemToObject(o, "k_px", cli_json_number(fdr_setup_k_px(s)));
}

void fdr_setup_print_normalisation(const struct fdr_setup *s)
{
	printf("  normalisation           %s, k_px = %.4g (eq. 2.3; "
	       "docs/normalisation.md)\n",
	       stray_normalisation_name(s->normalisation), fdr_setup_k_px(s));
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
