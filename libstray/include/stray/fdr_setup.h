/*
 * fdr_setup.h - what `stray fdr`, `stray exclusion` and the other
 * commands that answer with the FDR model share: which sensor, which
 * spectra, which FDR model extensions; and the step that turns them into
 * fluxes and an FDR model.  Their options: tools/fdr_options.h.
 */
#ifndef STRAY_FDR_SETUP_H
#define STRAY_FDR_SETUP_H

#include "stray/detector.h"
#include "stray/fdr.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"

struct fdr_setup {
	const char *sensor_spec;	/* --sensor, default st16-like */
	const char *sun, *vega, *qe;	/* spectrum overrides, or NULL */
	int poisson;			/* --noise poisson */
	int detector_noise;		/* --detector-noise */
	const char *map_path;		/* --map: non-uniform stray light */
	double moon_phase_deg;		/* --moon-phase, 0 = full */
	double rate;			/* --rate; NaN: the sensor's */
	double earth_albedo;		/* --earth-albedo (0.3) */
	double altitude_km;		/* --altitude-km (550) */
	int earth_given;		/* --earth-albedo was given */
	/* --normalisation: k_px of eq. 2.3 (docs/normalisation.md) */
	enum stray_normalisation normalisation;
	/* --detector, --detector-sigma (stray/detector.h); NULL / NaN: the
	 * sensor file's, else thesis / 3 */
	const char *detector_name;
	double detector_sigma;
	/* Filled by fdr_setup_load. */
	enum stray_detector_kind detector;
	struct stray_sensor sensor;
	struct stray_fluxes flux;
	struct stray_region_map map;
};

void fdr_setup_init(struct fdr_setup *s);

/* Load sensor, spectra and map; compute the reference fluxes. */
int fdr_setup_load(struct fdr_setup *s, struct stray_error *err);

/* The FDR model for a source of photon flux f_src. */
void fdr_setup_model(const struct fdr_setup *s, double f_src,
		     struct stray_fdr_model *m);

/* The chosen detector with its thresholds for the model m. */
int fdr_setup_detector(const struct fdr_setup *s,
		       const struct stray_fdr_model *m, struct stray_detector *d,
		       struct stray_error *err);

/* The attenuation both failure modes allow for the source of model m
 * (the thesis detector: eq. 2.18's alpha_required, as before). */
int fdr_setup_alpha_required(const struct fdr_setup *s,
			     const struct stray_fdr_model *m,
			     struct stray_detector_req *r,
			     struct stray_error *err);

/* eq. 2.3's k_px for the chosen normalisation and sensor. */
double fdr_setup_k_px(const struct fdr_setup *s);

/* The Moon's photon flux at the chosen phase. */
double fdr_setup_moon_flux(const struct fdr_setup *s);

/* The sunlit Earth's photon flux at the chosen albedo and altitude. */
int fdr_setup_earth_flux(const struct fdr_setup *s, double *flux,
			 struct stray_error *err);

#endif /* STRAY_FDR_SETUP_H */
