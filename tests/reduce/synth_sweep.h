/*
 * synth_sweep.h - a synthetic lab sweep for the reduction's tests: FITS
 * frames and manifest.csv (docs/formats.md) rendered from a known lens
 * curve through everything the lab adds (thesis §3.1-3.2): dark offsets
 * per Bayer read channel, dark current, read and shot noise, ambient light
 * and atmospheric scatter, ND filters, exposure changes, hot and dead
 * pixels, transient saturated spots, source drift and two ghosts.
 *
 * The truth (curve, ghost positions, bad pixels) stays in this file's
 * output struct; the reduction is never told any of it.
 */
#ifndef STRAY_TESTS_SYNTH_SWEEP_H
#define STRAY_TESTS_SYNTH_SWEEP_H

#include <stddef.h>

#define SYNTH_ANGLES_MAX 64
#define SYNTH_PIX_MAX 64
#define SYNTH_ENTRIES_MAX 1024

struct synth_config {
	size_t n_rows, n_cols;	/* stored frame size */
	int sampled;		/* rows in pairs spread over the detector */
	long col0, row0;
	double theta_step_deg;
	size_t n_angles;	/* 0, step, ..., (n-1) step */
	int repeats;		/* frames per group */
	int darks_per_exp;
	int revisit;		/* on-axis again at the end */
	double drift;		/* relative source change over the sweep */
	int monitor;		/* write MONITOR (the source reading) */
	int ghosts;
	int n_hot, n_dead;
	int sat_spots;		/* transient saturated 3x3 spots */
	int amb_longer;		/* AMBIENT at the next longer exposure */
	int two_pass;		/* all FULL frames, then all AMBIENT */
	unsigned long seed;
};

/* The defaults of the hidden-effect test (64 x 96 px, 0..14 deg). */
void synth_default(struct synth_config *c);

struct synth_entry {
	char file[64];
	const char *type;
	double angle_deg, exptime_s, ndtrans;
	long seqnum;
};

struct synth_truth {
	size_t n_angles;
	double theta_deg[SYNTH_ANGLES_MAX];
	double alpha[SYNTH_ANGLES_MAX];		/* eq. 3.12, exact */
	/* Ghost centres (detector column), NaN where not rendered. */
	double ghost_col[2][SYNTH_ANGLES_MAX];
	double ghost_rel[2][SYNTH_ANGLES_MAX];	/* ghost power / P(theta) */
	size_t n_hot, n_dead;
	long hot[SYNTH_PIX_MAX][2], dead[SYNTH_PIX_MAX][2];	/* row, col */
	size_t n_sat_spots;
	size_t n_entries;
	struct synth_entry entry[SYNTH_ENTRIES_MAX];
};

/* Render the sweep into dir (created); 0 on success, -1 with a message. */
int synth_write_sweep(const char *dir, const struct synth_config *c,
		      struct synth_truth *t);

/*
 * Rewrite dir/manifest.csv from t's entries with fresh SHA-256s, leaving
 * out those for which skip(entry, ctx) is true (skip may be NULL).
 */
int synth_write_manifest(const char *dir, const struct synth_truth *t,
			 int (*skip)(const struct synth_entry *, void *),
			 void *ctx);

#endif /* STRAY_TESTS_SYNTH_SWEEP_H */
