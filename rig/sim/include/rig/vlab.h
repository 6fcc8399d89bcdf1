/*
 * vlab.h - the virtual lab behind the simulated camera: what a lens on
 * the rotation stage would see of a collimated lamp beam (thesis §3.1-3.2,
 * table 3.1).  Each effect has its own knob, so a test can hide one:
 *   lamp with linear drift; lens response alpha(theta) with a column
 *   gradient off axis and ghost reflections that move with theta; room
 *   ambient and atmospheric scatter (both present with the beam blocked);
 *   dark current, per-channel Bayer bias, read and shot noise, hot pixels,
 *   saturation.  Units are detector counts (DN); the gain converts to
 *   electrons for the shot noise.
 */
#ifndef RIG_VLAB_H
#define RIG_VLAB_H

#include <stdint.h>

#define RIG_VLAB_GHOSTS_MAX 4
#define RIG_VLAB_CHANNELS 8	/* Bayer read channels, (row%2)*4 + col%4 */

struct rig_ghost {
	double amp;		/* peak rate relative to the on-axis rate */
	double col_at0;		/* detector column at theta = 0 */
	double px_per_deg;	/* drift of the column with theta */
	double sigma_px;	/* width across columns */
	double theta_c_deg, theta_w_deg;	/* where in theta it shows */
};

struct rig_vlab_cfg {
	double lamp_rate_dn_s;	/* direct per-pixel rate on axis, ND 1 */
	double lamp_drift_per_h;	/* fractional lamp change per hour */
	double lens_scale_deg;	/* e-folding angle of the lens response */
	double lens_floor;	/* far-off-axis response floor */
	double gradient;	/* column gradient amplitude times sin(theta) */
	int n_ghosts;
	struct rig_ghost ghost[RIG_VLAB_GHOSTS_MAX];
	double ambient_dn_s;	/* room light, lamp on, beam blocked or not */
	double atmos_frac;	/* atmospheric scatter / on-axis rate */
	double dark_dn_s;
	double bias_dn[RIG_VLAB_CHANNELS];
	double read_noise_dn;
	double gain_e_per_dn;
	double hot_frac;	/* fraction of hot pixels */
	double hot_dn_s;	/* their extra dark rate */
	int sat_dn;
	uint64_t seed;
};

struct rig_vlab_state {
	double theta_deg;
	double t_exp_s;
	double nd_trans;
	double t_s;		/* lab clock, for the lamp drift */
	int lamp_on, beam_blocked, shutter_open;
};

/* Defaults: an st16-like camera behind a lens that falls ~1e-3 by 45 deg. */
void rig_vlab_defaults(struct rig_vlab_cfg *cfg);

/* Render one frame of n_rows x n_cols pixels (rows given, from col0). */
void rig_vlab_render(const struct rig_vlab_cfg *cfg,
		     const struct rig_vlab_state *st, const uint16_t *rows,
		     int n_rows, int col0, int n_cols, uint64_t frame_seed,
		     uint16_t *px);

/* Truth: noiseless direct-light rate of one pixel, DN/s, lamp nominal,
 * ND 1, no drift (eq. 3.8: J_i proportional to alpha_px,i). */
double rig_vlab_direct_rate(const struct rig_vlab_cfg *cfg, double theta_deg,
			    int row, int col);

/* Truth: alpha_lens = P(theta)/P(0) over a row window (eq. 3.9-3.12). */
double rig_vlab_lens_alpha(const struct rig_vlab_cfg *cfg, double theta_deg,
			   const uint16_t *rows, int n_rows, int col0,
			   int n_cols);

/* Lamp output relative to nominal at lab time t_s (the drift). */
double rig_vlab_lamp_factor(const struct rig_vlab_cfg *cfg, double t_s);

/* Bayer read channel of a detector pixel. */
int rig_vlab_channel(int row, int col);

#endif /* RIG_VLAB_H */
