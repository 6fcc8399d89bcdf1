/*
 * frame.c - one frame's assessment: inputs checked, bodies located, false
 * stars from each (thesis eq. 2.18), exclusion flags with hysteresis.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fdrfw/ephem.h"
#include "fdrfw/fdrfw.h"
#include "fdrfw/vec.h"
#include "source_fdr.h"
#include "stray/fdr.h"
#include "stray/photometry.h"

/* Tolerances on inputs that must be unit length. */
#define UNIT_TOL 1e-3f
#define T_EXP_MAX_S 100.0f
#define POS_MAX_KM 2.0e6f	/* beyond the Moon: outside the model */
#define LN10 2.30258509299404568

int fdrfw_init(struct fdrfw_ctx *ctx, const struct fdrfw_table *table)
{
	int rc = fdrfw_table_check(table);

	(void)memset(ctx, 0, sizeof(*ctx));
	ctx->table = table;
	if (rc == FDRFW_OK)
		rc = fdrfw_fdr_init(ctx);
	if (rc != FDRFW_OK)
		ctx->table = NULL;
	return rc;
}

static int finite_vec(const float *v, unsigned n)
{
	unsigned i;

	for (i = 0; i < n; i++)
		if (!isfinite(v[i]))
			return 0;
	return 1;
}

static int unit_vec(const float v[3])
{
	return finite_vec(v, 3u) && fabsf(fdrfw_norm(v) - 1.0f) <= UNIT_TOL;
}

/* NaN, an unnormalised quaternion, a non-unit direction, a spacecraft
 * inside the Earth, an exposure out of range: the frame is invalid. */
static int inputs_valid(const struct fdrfw_input *in)
{
	float qn, r;

	if (!finite_vec(in->q, 4u) || !finite_vec(in->pos_km, 3u))
		return 0;
	qn = sqrtf(in->q[0] * in->q[0] + in->q[1] * in->q[1] +
		   in->q[2] * in->q[2] + in->q[3] * in->q[3]);
	r = fdrfw_norm(in->pos_km);
	if (!(fabsf(qn - 1.0f) <= UNIT_TOL) ||
	    !(r > FDRFW_EARTH_RADIUS_KM && r < POS_MAX_KM) ||
	    !(in->t_exp_s > 0.0f && in->t_exp_s <= T_EXP_MAX_S))
		return 0;
	return !in->use_given_dirs ||
	       (unit_vec(in->sun_dir) && unit_vec(in->moon_dir));
}

/* Sun and Moon directions from the spacecraft (given, or ephemeris with
 * the lunar parallax of the spacecraft's position). */
static int body_dirs(const struct fdrfw_input *in, float sun[3],
		     float moon[3])
{
	float r[3];
	unsigned i;

	if (in->use_given_dirs != 0)
		return fdrfw_unit(in->sun_dir, sun) &&
		       fdrfw_unit(in->moon_dir, moon);
	fdrfw_sun_dir(in->t_tt_s, sun);
	fdrfw_moon_pos_km(in->t_tt_s, r);
	for (i = 0; i < 3u; i++)
		r[i] -= in->pos_km[i];
	return fdrfw_unit(r, moon);
}

/* Lunar flux at this phase: the full Moon scaled by libstray's phase law,
 * in the core's real type. */
static stray_real moon_flux(const struct fdrfw_table *t, float phase_deg)
{
	stray_real m_full = (stray_real)t->moon_full_mag;
	stray_real dm = stray_moon_mag_at_phase(m_full, (stray_real)phase_deg) -
			m_full;

	/* eq. 2.2: F = F_full 10^(-0.4 dm), as exp: libm's pow is 3 KiB. */
	return (stray_real)t->f_moon_full_ph_s_m2 *
	       stray_exp(STRAY_R(-0.4 * LN10) * dm);
}

static void store(struct fdrfw_output *out, enum fdrfw_body b,
		  const struct fdrfw_source_result *r, uint32_t excl_flag)
{
	out->ln_fdr[b] = (float)r->ln_fdr;
	out->false_stars[b] = (float)stray_exp(r->ln_fdr);
	out->p_drs[b] = (float)r->p_drs;
	if (r->excluded != 0)
		out->flags |= excl_flag;
}

static void fail_frame(struct fdrfw_output *out)
{
	/* Conservative: every body excluded, no numbers to trust. */
	(void)memset(out, 0, sizeof(*out));
	out->flags = FDRFW_INPUT_INVALID | FDRFW_EXCLUDED_ALL;
	out->false_stars_total = NAN;
}

/* The bodies' angles, in-field and eclipse flags. */
static void locate(const struct fdrfw_table *t, const float b[3],
		   const float sun[3], const float moon[3],
		   const struct fdrfw_earth_cap *cap, struct fdrfw_output *out)
{
	float fov = t->fov_half_deg;
	float nadir_deg = fdrfw_angle_deg(b, cap->nadir);

	out->theta_deg[FDRFW_SUN] = fdrfw_angle_deg(b, sun);
	out->theta_deg[FDRFW_MOON] = fdrfw_angle_deg(b, moon);
	/* Earth: angle to the nearest point of its disc (0 on the disc). */
	out->theta_deg[FDRFW_EARTH] = fmaxf(0.0f, nadir_deg - cap->rho_deg);
	out->moon_phase_deg = 180.0f - fdrfw_angle_deg(sun, moon);
	if (out->theta_deg[FDRFW_SUN] < fov + FDRFW_SUN_RADIUS_DEG)
		out->flags |= FDRFW_SUN_IN_FOV;
	if (out->theta_deg[FDRFW_MOON] < fov + FDRFW_MOON_RADIUS_DEG)
		out->flags |= FDRFW_MOON_IN_FOV;
	if (out->theta_deg[FDRFW_EARTH] < fov)
		out->flags |= FDRFW_EARTH_IN_FOV;
	/* The Sun's centre behind the Earth's disc (conical shadow edge). */
	if (fdrfw_angle_deg(sun, cap->nadir) < cap->rho_deg)
		out->flags |= FDRFW_SUN_ECLIPSED;
}

/* The Moon is also excluded while in the field, where it saturates
 * (thesis §5.1), with the same hysteresis margin. */
static int moon_in_field_excluded(const struct fdrfw_ctx *ctx, float theta)
{
	const struct fdrfw_table *t = ctx->table;
	float edge = t->fov_half_deg + FDRFW_MOON_RADIUS_DEG;

	if ((ctx->latched & FDRFW_MOON_EXCLUDED) != 0u)
		edge += t->hysteresis_deg;
	return theta < edge;
}

static int assess(struct fdrfw_ctx *ctx, const float b[3],
		  const struct fdrfw_earth_cap *cap, struct fdrfw_output *out)
{
	const struct fdrfw_table *t = ctx->table;
	struct fdrfw_source_result r;
	uint32_t held = ctx->latched;
	int rc = 0;

	fdrfw_source_none(ctx, &r);	/* the Sun eclipsed */
	if (!(out->flags & FDRFW_SUN_ECLIPSED))
		rc |= fdrfw_point_source(ctx, (stray_real)t->f_sun_ph_s_m2,
			out->theta_deg[FDRFW_SUN],
			(held & FDRFW_SUN_EXCLUDED) != 0, &r);
	store(out, FDRFW_SUN, &r, FDRFW_SUN_EXCLUDED);
	rc |= fdrfw_point_source(ctx, moon_flux(t, out->moon_phase_deg),
		out->theta_deg[FDRFW_MOON],
		(held & FDRFW_MOON_EXCLUDED) != 0, &r);
	r.excluded |= moon_in_field_excluded(ctx, out->theta_deg[FDRFW_MOON]);
	store(out, FDRFW_MOON, &r, FDRFW_MOON_EXCLUDED);
	rc |= fdrfw_earth_source(ctx, cap, b, out->theta_deg[FDRFW_EARTH],
				 (held & FDRFW_EARTH_EXCLUDED) != 0, &r);
	store(out, FDRFW_EARTH, &r, FDRFW_EARTH_EXCLUDED);
	out->false_stars_total = out->false_stars[FDRFW_SUN] +
				 out->false_stars[FDRFW_MOON] +
				 out->false_stars[FDRFW_EARTH];
	return rc;
}

int fdrfw_frame(struct fdrfw_ctx *ctx, const struct fdrfw_input *in,
		struct fdrfw_output *out)
{
	float b[3], sun[3], moon[3];
	struct fdrfw_earth_cap cap;

	if (ctx->table == NULL || !inputs_valid(in) ||
	    !body_dirs(in, sun, moon) ||
	    !fdrfw_earth_cap(in->pos_km, sun, &cap) ||
	    (in->t_exp_s != ctx->i_sdt_t_exp_s &&
	     fdrfw_set_exposure(ctx, in->t_exp_s) != FDRFW_OK)) {
		fail_frame(out);
		return FDRFW_EINPUT;
	}
	fdrfw_boresight_renorm(in->q, b);	/* within UNIT_TOL of unit */
	(void)memset(out, 0, sizeof(*out));
	locate(ctx->table, b, sun, moon, &cap, out);
	if (assess(ctx, b, &cap, out) != 0) {
		fail_frame(out);
		return FDRFW_EINPUT;
	}
	ctx->latched = out->flags & FDRFW_EXCLUDED_ALL;
	return FDRFW_OK;
}
