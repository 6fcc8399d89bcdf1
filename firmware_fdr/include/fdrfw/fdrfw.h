/*
 * fdrfw.h - per-frame stray-light assessment on board (firmware_fdr).
 *
 * For each frame: the off-axis angle of the Sun, the Moon and the Earth,
 * the expected false stars from each (thesis eq. 2.3-2.18, evaluated by
 * libstray's own FDR core compiled into the module, in single precision on
 * the target: STRAY_REAL_FLOAT), and flags.  The caller owns the context;
 * nothing here allocates, recurses or keeps a mutable global.
 */
#ifndef FDRFW_FDRFW_H
#define FDRFW_FDRFW_H

#include <stdint.h>

#include "fdrfw/table.h"
#include "stray/fdr.h"

enum fdrfw_body { FDRFW_SUN = 0, FDRFW_MOON = 1, FDRFW_EARTH = 2,
		  FDRFW_BODIES = 3 };

/* Output flags (one bit each). */
#define FDRFW_SUN_EXCLUDED	(1u << 0)
#define FDRFW_MOON_EXCLUDED	(1u << 1)
#define FDRFW_EARTH_EXCLUDED	(1u << 2)
#define FDRFW_SUN_IN_FOV	(1u << 3)
#define FDRFW_MOON_IN_FOV	(1u << 4)
#define FDRFW_EARTH_IN_FOV	(1u << 5)
#define FDRFW_SUN_ECLIPSED	(1u << 6)
#define FDRFW_INPUT_INVALID	(1u << 7)
#define FDRFW_EXCLUDED_ALL \
	(FDRFW_SUN_EXCLUDED | FDRFW_MOON_EXCLUDED | FDRFW_EARTH_EXCLUDED)

/* Angular radii used for "in field of view" [deg]. */
#define FDRFW_SUN_RADIUS_DEG 0.2666f
#define FDRFW_MOON_RADIUS_DEG 0.2590f

struct fdrfw_input {
	float q[4];		/* attitude (w, x, y, z), inertial -> sensor */
	float t_exp_s;		/* exposure of this frame */
	float pos_km[3];	/* spacecraft, geocentric inertial */
	/* Either time for the on-board ephemeris ... */
	int32_t t_tt_s;		/* seconds since J2000.0 TT */
	/* ... or given directions (used when use_given_dirs != 0). */
	int use_given_dirs;
	float sun_dir[3];	/* unit, towards the Sun */
	float moon_dir[3];	/* unit, spacecraft -> Moon */
};

struct fdrfw_output {
	uint32_t flags;
	float theta_deg[FDRFW_BODIES];	/* off axis (Earth: nearest limb) */
	float ln_fdr[FDRFW_BODIES];	/* ln of expected false stars */
	float false_stars[FDRFW_BODIES];
	float false_stars_total;
	/* The designed reference star's detection probability under each
	 * body's light (a detector table's model; NaN for THESIS, whose
	 * eq. 2.18 has no lost-star model on board). */
	float p_drs[FDRFW_BODIES];
	float moon_phase_deg;		/* 0 = full */
};

struct fdrfw_ctx {
	const struct fdrfw_table *table;	/* checked at init */
	uint32_t latched;	/* exclusion flags held by hysteresis */
	float i_sdt_t_exp_s;	/* exposure the cached threshold is for */
	stray_real i_sdt_e;	/* eq. 2.16 threshold for that exposure */
	stray_real z_drs;	/* Q^-1(Pr_drs), the ground's, checked */
	stray_real ln_fdr_tolerated;	/* ln of the table's tolerated FDR */
	/* The FDR model (eq. 2.3-2.18) from the table, kept here rather than
	 * rebuilt on the stack of every call; a source sets its flux. */
	struct stray_fdr_model model;
};

/*
 * Check the table (magic, CRC, ranges) and bind it; z = Q^-1(Pr_drs)
 * (eq. 2.16) is the ground's, checked here by Q(z).  On failure the
 * context stays unbound and every frame reports FDRFW_INPUT_INVALID.
 */
int fdrfw_init(struct fdrfw_ctx *ctx, const struct fdrfw_table *table);

/*
 * The detection threshold I_sdt (eq. 2.16) for an exposure, cached in the
 * context.  z = Q^-1(Pr_drs) does not depend on the exposure and is solved
 * once at init, so this is the closed form I_drs + z sqrt(I_drs): no root
 * search in the frame loop.  fdrfw_frame calls it when a frame's exposure
 * differs from the cached one.  A detector table's grid is for its
 * nominal exposure: another one is FDRFW_EINPUT (one table per exposure).
 */
int fdrfw_set_exposure(struct fdrfw_ctx *ctx, float t_exp_s);

/* Assess one frame.  Returns FDRFW_OK or FDRFW_EINPUT (flag also set). */
int fdrfw_frame(struct fdrfw_ctx *ctx, const struct fdrfw_input *in,
		struct fdrfw_output *out);

#endif /* FDRFW_FDRFW_H */
