/*
 * frames_run.h - the analysis side of `stray frames` (issue 13 items 4-5):
 * the false-star models for a rendered frame, the matching of detections
 * to the true stars, and the diagnosis of a model-measurement
 * disagreement.  It never reads the renderer's truth settings: only the
 * frames, the star list a catalogue would give, and the nominal model.
 */
#ifndef STRAY_FRAMES_FRAMES_RUN_H
#define STRAY_FRAMES_FRAMES_RUN_H

#include <stddef.h>

#include "frames/frames_detect.h"
#include "stray/fdr.h"
#include "stray/fdr_field.h"
#include "stray/frames.h"
#include "stray/sensor.h"

/* What the analysis knows: the nominal (uniform or mapped) model. */
struct frames_model {
	struct stray_fdr_model m;	/* eq. 2.3-2.18; n_tot = rendered px */
	double alpha_eff;		/* k_px alpha: what eq. 2.3 needs */
	double stray_e;			/* mean stray e-/px */
	double dark_e, read_noise_e, quant_var_e;
	double i_sdt_e;			/* eq. 2.16 with detector noise */
	double pixel_threshold_e;	/* threshold detector, from the DRS */
	int min_px;
	struct stray_window_corr win;	/* the disk window */
	int cols, rows;
};

struct frames_rates {
	double thesis;			/* eq. 2.18, Gaussian, no det. noise */
	double model;			/* eq. 2.18, Poisson + read noise */
	double sliding;			/* extended: thesis detector */
	double clusters;		/* extended: threshold detector */
};

/* Fill the model for a frame; map (or NULL) is the known stray map. */
int frames_model_init(struct frames_model *fm, const struct stray_sensor *s,
		      double f_src, double f_drs, double k_px, double alpha,
		      int cols, int rows, const struct stray_region_map *map,
		      struct stray_error *err);

/* Rates per rendered frame of every model. */
int frames_model_rates(const struct frames_model *fm,
		       struct frames_rates *r, struct stray_error *err);

/*
 * The attenuation alpha (the curve's units: k_px divided out) at which a
 * full detector sees `rate` false stars per image: thesis model as the
 * toolkit has it (Gaussian, no detector noise, k_px = 1), eq. 2.18 with
 * this normalisation and detector noise, and the sliding-window
 * extension (what the thesis detector really does).
 */
struct frames_alpha_req { double thesis_k1, model, extended; };
int frames_alpha_required(const struct frames_model *fm,
			  const struct stray_sensor *s, double k_px,
			  double rate, struct frames_alpha_req *a,
			  struct stray_error *err);

/* Detector thresholds for the camera: I_sdt and the pixel threshold. */
void frames_detect_cfg_init(struct frames_detect_cfg *c,
			    const struct frames_model *fm,
			    const struct stray_sensor *s);

/*
 * Detections matching no star of at least min_e within match_px; the
 * false ones' positions are appended to fx/fy (up to max_f) when given.
 */
size_t frames_count_false(const struct frames_detect_out *o,
			  const struct stray_star *stars, size_t n_stars,
			  double min_e, double match_px, float *fx, float *fy,
			  size_t *n_f, size_t max_f);

/* Accumulated evidence over a run, for the diagnosis. */
struct frames_evidence {
	int tiles_x, tiles_y;
	double *tile_sum;		/* tiles: background e- summed over frames */
	long frames;
	float *fx, *fy;			/* false-star positions (all frames) */
	size_t n_f, max_f;
};

/*
 * Compare measured and modelled false stars (per frame, Poisson sigma)
 * and, when they disagree, name the cause the frames show: a stray-light
 * gradient (plane fit of the background tiles), hot pixels (false stars
 * recurring at one place), or a background level off the model.  Writes
 * a one-line verdict to text; returns 1 on disagreement, 0 otherwise.
 */
int frames_diagnose(const struct frames_model *fm,
		    const struct frames_evidence *ev, double measured,
		    double model, int tile_px, char *text, size_t size);

#endif /* STRAY_FRAMES_FRAMES_RUN_H */
