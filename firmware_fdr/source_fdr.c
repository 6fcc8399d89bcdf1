/*
 * source_fdr.c - expected false stars per source (thesis eq. 2.3-2.18).
 *
 * Precision: the module's geometry is single precision, but the FDR
 * itself is libstray's double-precision core (fdr.c, tail.c), compiled
 * into the module unchanged, so ground and flight share one equation set.
 * Its argument is ln Q(I_sdt / sigma) with I_sdt/sigma up to ~40, where a
 * float would keep only 3 digits of ln FDR; the table's floats (alpha,
 * fluxes, I_sdt) carry 7 digits, well inside the 1e-3 agreement asked.
 * I_sdt (eq. 2.16), a root search, is done on the ground for the nominal
 * exposure and cached per exposure in the context.
 */
#include <math.h>
#include <stddef.h>

#include "fdrfw/vec.h"
#include "source_fdr.h"
#include "stray/fdr.h"

#define INV_PI 0.318309886183790672f

/* The thesis model (Gaussian, uniform light) for this frame's source. */
static void model_of(const struct fdrfw_table *t, float t_exp_s,
		     double f_src, struct stray_fdr_model *m)
{
	m->f_src_ph_s_m2 = f_src;
	m->f_drs_ph_s_m2 = (double)t->f_drs_ph_s_m2;
	m->t_exp_s = (double)t_exp_s;
	m->a_px_m2 = (double)t->a_px_m2;
	m->a_cs_m2 = (double)t->a_cs_m2;
	m->n_pps = (double)t->n_pps;
	m->n_tot = (double)t->n_tot;
	m->pr_drs = (double)t->pr_drs;
	m->read_noise_e = 0.0;
	m->dark_current_e_s = 0.0;
	m->noise = STRAY_NOISE_GAUSS;
	m->map = NULL;
}

int fdrfw_set_exposure(struct fdrfw_ctx *ctx, float t_exp_s)
{
	struct stray_fdr_model m;
	double i_sdt;

	if (ctx->table == NULL || !(t_exp_s > 0.0f && t_exp_s <= 100.0f))
		return FDRFW_EINPUT;
	/* eq. 2.16: I_sdt = I_drs + z sqrt(I_drs), Q(z) = Pr_drs, solved by
	 * libstray (a bounded Brent search); the source flux plays no part. */
	model_of(ctx->table, t_exp_s, 0.0, &m);
	if (stray_fdr_threshold(&m, &i_sdt, NULL) != 0)
		return FDRFW_EINPUT;
	ctx->i_sdt_e = i_sdt;
	ctx->i_sdt_t_exp_s = t_exp_s;
	return FDRFW_OK;
}

/* eq. 2.18: ln FDR at attenuation alpha; -inf for no light. */
static int log_fdr(const struct fdrfw_ctx *ctx, float t_exp_s, double f_src,
		   double alpha, double *ln)
{
	struct stray_fdr_model m;

	model_of(ctx->table, t_exp_s, f_src, &m);
	return stray_fdr_log_rate(&m, alpha, ctx->i_sdt_e, ln, NULL);
}

static float envelope_angle(const struct fdrfw_table *t, float theta_deg,
			    int latched)
{
	return latched ? theta_deg - t->hysteresis_deg : theta_deg;
}

int fdrfw_point_source(const struct fdrfw_ctx *ctx, float t_exp_s,
		       double f_src, float theta_deg, int latched,
		       struct fdrfw_source_result *res)
{
	const struct fdrfw_table *t = ctx->table;
	float env = fdrfw_envelope_at(t, envelope_angle(t, theta_deg, latched));
	double ln_env = -INFINITY;
	int rc;

	rc = log_fdr(ctx, t_exp_s, f_src,
		     (double)fdrfw_alpha_at(t, theta_deg), &res->ln_fdr);
	if (rc == 0)
		rc = log_fdr(ctx, t_exp_s, f_src, (double)env, &ln_env);
	/* FDR rises with alpha: FDR(envelope) >= R iff envelope >= alpha_req
	 * (fig. 2.7), i.e. theta before the exclusion angle (fig. 5.1). */
	res->excluded = rc == 0 && ln_env >= log((double)t->fdr_tolerated);
	return rc;
}

int fdrfw_earth_source(const struct fdrfw_ctx *ctx, float t_exp_s,
		       const struct fdrfw_earth_cap *cap, const float b[3],
		       int latched, struct fdrfw_source_result *res)
{
	const struct fdrfw_table *t = ctx->table;
	/* eq. 2.3 for an extended source: I_px = t A_px sum alpha_k F_k, with
	 * F_k = L_k dOmega_k and L_k = albedo E_sun cos(i_k) / pi. */
	float f_tot = 0.0f, fa = 0.0f, fe = 0.0f;
	double ln_env = -INFINITY;
	unsigned k;
	int rc;

	for (k = 0; k < FDRFW_EARTH_NODES; k++) {
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
		res->ln_fdr = -INFINITY;
		res->excluded = 0;
		return 0;
	}
	rc = log_fdr(ctx, t_exp_s, (double)f_tot, (double)(fa / f_tot),
		     &res->ln_fdr);
	if (rc == 0)
		rc = log_fdr(ctx, t_exp_s, (double)f_tot, (double)(fe / f_tot),
			     &ln_env);
	res->excluded = rc == 0 && ln_env >= log((double)t->fdr_tolerated);
	return rc;
}
