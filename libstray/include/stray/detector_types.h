/*
 * detector_types.h - the named detectors' kinds and parameters (issue 28; detector.h
 * gives the models).
 * Freestanding C99, no heap (stray/detector.h includes it).
 */
#ifndef STRAY_DETECTOR_TYPES_H
#define STRAY_DETECTOR_TYPES_H

#include "stray/fdr.h"
#include "stray/fdr_field.h"

enum stray_detector_kind {
	STRAY_DET_THESIS = 0,
	STRAY_DET_WINDOW = 1,
	STRAY_DET_THRESHOLD = 2,
	STRAY_DET_TETRA3 = 3
};
#define STRAY_DET_COUNT 4

/* Window positions near a star searched by the WINDOW model. */
#define STRAY_DET_POS_MAX 21

/* THRESHOLD's lost-star model (detector_blob.c): the 8-connected lattice
 * animals of 1..min_px-1 cells through a pixel (1 + 8 + 60 + 440 = 509
 * for min_px 5), each with its 8-neighbour perimeter; cells and perimeter
 * as codes (dy + 4) * 9 + dx + 4 about that pixel. */
#define STRAY_DET_BLOB_PX_MAX 5		/* min_px the table covers */
#define STRAY_DET_ANIMALS_MAX 512
#define STRAY_DET_PERIM_MAX 24
struct stray_det_animal {
	unsigned char n_cell, n_per;
	unsigned char cell[STRAY_DET_BLOB_PX_MAX - 1];
	unsigned char per[STRAY_DET_PERIM_MAX];
};

struct stray_detector {
	enum stray_detector_kind kind;
	stray_real sigma_k;		/* TETRA3: threshold in frame sigmas */
	unsigned min_px;		/* THRESHOLD, TETRA3: least blob area */
	stray_real psf_sigma_px;	/* Gaussian PSF sigma of a star */
	stray_real window_r_px;		/* disk window radius (n_pps) */
	/* Filled by stray_detector_setup from the model. */
	stray_real i_sdt_e;		/* THESIS, WINDOW: eq. 2.16 */
	stray_real pixel_t_e;		/* THRESHOLD: pixel threshold */
	struct stray_window_corr win;	/* WINDOW: neighbour overlaps */
	stray_real pos_rho;		/* WINDOW: mean overlap of positions */
	/* WINDOW, THRESHOLD: rms of the error of the detector's background
	 * estimate per pixel, in units of the mean stray level: the focal
	 * map's structure its estimator cannot follow (stray frames: the map
	 * against its 128 px tiles' bilinear, frames_mapterm.h).  0: none
	 * (uniform light, or a region map without places). */
	stray_real bg_resid_rel;
	/* THRESHOLD, min_px <= STRAY_DET_BLOB_PX_MAX: the animals smaller
	 * than min_px through a pixel (0: the Poisson-binomial rule). */
	unsigned n_animal;
	struct stray_det_animal animal[STRAY_DET_ANIMALS_MAX];
};

/* The background-error term: STRAY_DET_RESID_NODES Gauss-Hermite nodes
 * (z, weight) of N(0, 1), the error at node k being z_k bg_resid_rel
 * I_px(alpha); n = 1 (z 0, weight 1) when bg_resid_rel is 0 or the
 * detector follows the frame (THESIS, TETRA3). */
#define STRAY_DET_RESID_NODES 7

#endif /* STRAY_DETECTOR_TYPES_H */
