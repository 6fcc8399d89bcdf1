/*
 * source_fdr.c - expected false stars per source (thesis eq. 2.3-2.18).
 *
 * Precision: the FDR is libstray's core (fdr.c, tail.c, root.c) compiled
 * into the module unchanged, in its stray_real type: single precision on
 * the target (STRAY_REAL_FLOAT, the M4F's FPU has no double), double on the
 * host.  Its argument is ln Q(I_sdt / sigma); where the vectors are judged
 * (FDR above 1e-30, I_sdt/sigma below ~13) a float keeps ln FDR to ~1e-5,
 * and at I_sdt/sigma ~ 40 (ln Q = -804) to ~1e-4, inside the 1e-3 asked.
 *
 * The model lives in the caller's context, filled from the table once at
 * init, so a frame never builds one on its stack.  z = Q^-1(Pr_drs) of
 * eq. 2.16 is solved once there too (a Brent search); an exposure change
 * is then the closed form I_sdt = I_drs + z sqrt(I_drs).
 */
#include <math.h>
#include <stddef.h>

#include "fdrfw/model_map.h"
#include "fdrfw/vec.h"
#include "source_fdr.h"
#include "stray/fdr.h"
#include "stray/tail.h"

#define INV_PI 0.318309886183790672f
/* The Earth: below this ln FDR (1e-30) its light is reported as none. */
#define LN_FDR_NEGLIGIBLE STRAY_R(-69.0775527898)

/* eq. 2.18: ln FDR at attenuation alpha; -inf for no light. */
static int log_fdr(struct fdrfw_ctx *ctx, stray_real f_src, float alpha,
		   stray_real *ln)
{
	ctx->model.f_src_ph_s_m2 = f_src;
	return stray_fdr_log_rate(&ctx->model, (stray_real)alpha, ctx->i_sdt_e,
				  ln, NULL);
}

/* |a - b| <= tol (NaN fails). */
static int near(stray_real a, stray_real b, stray_real tol)
{
	return ((a - b) <= tol) && ((b - a) <= tol);
}

/* The Sun's alpha_req is where its flag turns on: eq. 2.18 gives the
 * tolerated rate there (fig. 2.7, ln within 0.01); a detector's grid is
 * off just below it and on just above (the binding mode is at its
 * requirement there: the ground put a node on it). */
static int sun_req_ok(struct fdrfw_ctx *ctx)
{
	const struct fdrfw_table *t = ctx->table;
	stray_real f = (stray_real)t->f_sun_ph_s_m2;
	float a = t->alpha_req_sun;
	struct fdrfw_source_result lo;
	struct fdrfw_source_result hi;
	stray_real ln_req = STRAY_HUGE;
	int ok;

	if (t->n_det > 0u) {
		fdrfw_grid_source(ctx, f, a * 0.999f, a * 0.999f, &lo);
		fdrfw_grid_source(ctx, f, a * 1.001f, a * 1.001f, &hi);
		ok = 0;
		if ((lo.excluded == 0) && (hi.excluded != 0)) {
			ok = 1;
		}
	} else {
		(void)log_fdr(ctx, f, a, &ln_req);
		ok = near(ln_req, ctx->ln_fdr_tolerated, STRAY_R(0.01));
	}
	return ok;
}

int fdrfw_fdr_init(struct fdrfw_ctx *ctx)
{
	const struct fdrfw_table *t = ctx->table;
	struct stray_fdr_model *m = &ctx->model;
	struct fdrfw_source_result sun;	/* source_result sets both */
	stray_real ln_pr;
	int rc = (int)FDRFW_OK;

	/* The thesis model (Gaussian, uniform light, no detector noise). */
	fdrfw_model_from_table(t, m);
	/* z = Q^-1(Pr_drs) of eq. 2.16 is solved on the ground (a root
	 * search is 0.8 KiB of flight code): here Q(z) must give Pr_drs,
	 * ln within 1e-4 of it (float rounding of z: < 3e-6). */
	ctx->z_drs = (stray_real)t->z_drs;
	ln_pr = stray_log(m->pr_drs);
	/* I_sdt at the nominal exposure as the ground solved it: eq. 2.16
	 * of the table's own model, to float rounding. */
	ctx->i_sdt_e = (stray_real)t->i_sdt_e;
	ctx->i_sdt_t_exp_s = t->t_exp_nominal_s;
	ctx->ln_fdr_tolerated = stray_log((stray_real)t->fdr_tolerated);
	if (stray_fdr_model_check(m, NULL) != 0) {
		rc = (int)FDRFW_ERANGE;
	} else if (!near(stray_log_gauss_q(ctx->z_drs), ln_pr,
			 STRAY_R(1e-4) * (STRAY_R(0.01) - ln_pr))) {
		rc = FDRFW_EFIELD_OF(z_drs);
	} else if (!near(stray_fdr_threshold_gauss(m, ctx->z_drs),
			 ctx->i_sdt_e, STRAY_R(1e-3) * ctx->i_sdt_e)) {
		rc = FDRFW_EFIELD_OF(i_sdt_e);
	} else if (sun_req_ok(ctx) == 0) {
		rc = FDRFW_EFIELD_OF(alpha_req_sun);
	} else {
		/* The Sun on the boresight is excluded, whatever the table
		 * says. */
		(void)fdrfw_point_source(ctx, (stray_real)t->f_sun_ph_s_m2,
					 0.0f, 0, &sun);
		if (sun.excluded == 0) {
			rc = FDRFW_EFIELD_OF(exclusion_sun_deg);
		}
	}
	return rc;
}

int fdrfw_set_exposure(struct fdrfw_ctx *ctx, float t_exp_s)
{
	if (ctx->table == NULL || !(t_exp_s > 0.0f && t_exp_s <= 100.0f) ||
	    /* a detector's grid holds its nominal exposure only */
	    ((ctx->table->n_det > 0u) &&
	     (t_exp_s != ctx->table->t_exp_nominal_s)))
		return FDRFW_EINPUT;
	/* eq. 2.16: I_sdt = I_drs + z sqrt(I_drs), Q(z) = Pr_drs; the source
	 * flux plays no part. */
	ctx->model.t_exp_s = (stray_real)t_exp_s;
	ctx->i_sdt_e = stray_fdr_threshold_gauss(&ctx->model, ctx->z_drs);
	ctx->i_sdt_t_exp_s = t_exp_s;
	return FDRFW_OK;
}

static float envelope_angle(const struct fdrfw_table *t, float theta_deg,
			    int latched)
{
	return latched ? theta_deg - t->hysteresis_deg : theta_deg;
}

/* A detector table's value v at grid place x (node units): linear
 * between nodes, the end nodes' beyond them.  Node 0 lies 5 decades of
 * light under the Sun's binding background (darker is the dark sky), the
 * last past every requirement; NaN reads the last (the flag set). */
static stray_real grid_at(const float *v, stray_real x)
{
	stray_real r;

	if (!(x < (STRAY_R(FDRFW_DET_MAX) - STRAY_R(1.0)))) {
		r = (stray_real)v[FDRFW_DET_MAX - 1];
	} else if (!(x > STRAY_R(0.0))) {
		r = (stray_real)v[0];
	} else {
		unsigned i = (unsigned)x;

		r = (stray_real)v[i] + (x - (stray_real)i) *
		    ((stray_real)v[i + 1u] - (stray_real)v[i]);
	}
	return r;
}

/* The grid place of the light f_src alpha: ln I_px (eq. 2.3). */
static stray_real grid_x(struct fdrfw_ctx *ctx, stray_real f_src, float alpha)
{
	const struct fdrfw_table *t = ctx->table;

	ctx->model.f_src_ph_s_m2 = f_src;
	return (stray_log(stray_fdr_pixel_photons(&ctx->model,
						  (stray_real)alpha)) -
		(stray_real)t->det_u0) / (stray_real)t->det_du;
}

void fdrfw_grid_source(struct fdrfw_ctx *ctx, stray_real f_src, float alpha,
		       float env, struct fdrfw_source_result *res)
{
	const struct fdrfw_table *t = ctx->table;
	stray_real x = grid_x(ctx, f_src, alpha);
	stray_real xe = grid_x(ctx, f_src, env);
	stray_real lf = grid_at(t->det_ln_false, x);

	res->ln_fdr = (lf > (stray_real)FDRFW_DET_LN_FLOOR) ? lf : -STRAY_HUGE;
	res->p_drs = grid_at(t->det_p_drs, x);
	/* both failure modes at the envelope: too many false stars, or the
	 * reference star lost (both monotone in the light: fdrfw_table_check) */
	res->excluded = (grid_at(t->det_ln_false, xe) >=
			 ctx->ln_fdr_tolerated) ||
			(grid_at(t->det_p_drs, xe) < (stray_real)t->pr_drs);
	res->negligible = !(xe > STRAY_R(0.0));
}

void fdrfw_source_none(const struct fdrfw_ctx *ctx,
		       struct fdrfw_source_result *res)
{
	const struct fdrfw_table *t = ctx->table;

	res->ln_fdr = -STRAY_HUGE;
	res->p_drs = (t->n_det > 0u) ? (stray_real)t->det_p_drs[0] :
		     (stray_real)NAN;
	res->excluded = 0;
	res->negligible = 1;
}

/* FDR rises with alpha: FDR(envelope) >= R iff envelope >= alpha_req
 * (fig. 2.7), i.e. theta before the exclusion angle (fig. 5.1).  alpha
 * never passes the envelope, so below ln 1e-30 there (where the vectors
 * judge no digits) the rate is reported as none, without its own FDR.
 * A detector table reads its grid instead (fdrfw_grid_source). */
static int source_result(struct fdrfw_ctx *ctx, stray_real f_src,
			 float alpha, float env,
			 struct fdrfw_source_result *res)
{
	stray_real ln_env = -STRAY_HUGE;
	int rc = 0;

	if (ctx->table->n_det > 0u) {
		fdrfw_grid_source(ctx, f_src, alpha, env, res);
	} else {
		rc = log_fdr(ctx, f_src, env, &ln_env);
		res->ln_fdr = -STRAY_HUGE;
		res->p_drs = (stray_real)NAN;
		res->negligible = !((rc == 0) &&
				    (ln_env >= LN_FDR_NEGLIGIBLE));
		if (res->negligible == 0) {
			rc = log_fdr(ctx, f_src, alpha, &res->ln_fdr);
		}
		res->excluded = rc == 0 && ln_env >= ctx->ln_fdr_tolerated;
	}
	return rc;
}

int fdrfw_point_source(struct fdrfw_ctx *ctx, stray_real f_src,
		       float theta_deg, int latched,
		       struct fdrfw_source_result *res)
{
	const struct fdrfw_table *t = ctx->table;

	return source_result(ctx, f_src, fdrfw_alpha_at(t, theta_deg),
		fdrfw_envelope_at(t, envelope_angle(t, theta_deg, latched)),
		res);
}

int fdrfw_earth_source(struct fdrfw_ctx *ctx,
		       const struct fdrfw_earth_cap *cap, const float b[3],
		       float theta_deg, int latched,
		       struct fdrfw_source_result *res)
{
	const struct fdrfw_table *t = ctx->table;
	/* eq. 2.3 for an extended source: I_px = t A_px sum alpha_k F_k, with
	 * F_k = L_k dOmega_k and L_k = albedo E_sun cos(i_k) / pi. */
	float f_tot = 0.0f, fa = 0.0f, fe = 0.0f;
	/* Every node lies at least theta_deg (the cap's nearest point, to
	 * ~1e-5 deg in float: 0.01 allowed) off axis, where the envelope
	 * (never below alpha, never rising outward) bounds alpha and the
	 * envelope at every node, latched or not. */
	float env = fdrfw_envelope_at(t, theta_deg - t->hysteresis_deg - 0.01f);
	unsigned k;

	/* All the cap's light there (cos i <= 1; the quadrature's solid
	 * angle within 1.1 of 2 pi (1 - cos rho), 1.0105 at worst) bounds the
	 * rate, which rises with alpha F (eq. 2.18).  Under the floor of
	 * source_result, the night side's answer without the nodes: the flag
	 * is exact (the floor is under the tolerated rate, >= 1e-9 by the
	 * table's check), the rate below 1e-30 reported as none. */
	(void)source_result(ctx, (stray_real)(t->earth_albedo *
			  t->f_sun_ph_s_m2 * 2.2f * cap->one_minus_cos_rho),
			  env, env, res);
	for (k = 0u; (k < FDRFW_EARTH_NODES) && (res->negligible == 0); k++) {
		struct fdrfw_earth_node node;
		float f, theta;

		fdrfw_earth_node(cap, k, &node);
		if (!(node.cos_sun > 0.0f))
			continue;	/* night: no light, skip the lookups */
		f = t->earth_albedo * t->f_sun_ph_s_m2 * node.cos_sun *
		    INV_PI * node.omega_sr;
		theta = fdrfw_angle_deg(b, node.dir);
		f_tot += f;
		fa += f * fdrfw_alpha_at(t, theta);
		fe += f * fdrfw_envelope_at(t,
					    envelope_angle(t, theta, latched));
	}
	if (!(f_tot > 0.0f)) {	/* the night side: no light at all */
		fdrfw_source_none(ctx, res);
		return 0;
	}
	return source_result(ctx, (stray_real)f_tot, fa / f_tot, fe / f_tot,
			     res);
}
