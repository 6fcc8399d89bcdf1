/*
 * fdr.c - false detections per image from the system attenuation
 * (thesis §2.3, eq. 2.3-2.18).  Freestanding: linked by firmware_fdr.
 *
 * Notation follows the thesis: I_px expected stray photons per pixel
 * (eq. 2.3), n_pps pixels per star window, I_drs the designed reference
 * star's photons (eq. 2.12), I_sdt the star-detection threshold (eq. 2.16),
 * Pr_fd the false-detection probability of one window (eq. 2.17).
 *
 * Extensions (off by default): detector noise adds a variance
 * b = n_pps (read_noise^2 + dark_current t_exp) to every window, dark mean
 * subtracted; the Poisson model uses exact Poisson tails through the
 * regularized incomplete gamma function, with the Gaussian part of b
 * folded in by the shifted-Poisson approximation of Snyder, Hammoud &
 * White (1993, JOSA A 10, 1014); a region map replaces uniform light.
 * Numbers are stray_real: double, or float in flight builds (config.h).
 */
#include "stray/fdr.h"
#include "stray/root.h"
#include "stray/tail.h"

/* Past this window mean the Poisson tail is evaluated as a Gaussian: the
 * threshold is then < 1e-2 standard deviations out, where the skew error
 * z^3 / (6 sqrt(mu)) is below 1e-9 (the series would need > 1e5 terms). */
#define POISSON_GAUSS_MEAN STRAY_R(1e8)

#define ALPHA_SEARCH_MIN STRAY_R(1e-30)
#define ALPHA_SEARCH_MAX STRAY_R(1e12)

static int positive(stray_real v)
{
	return isfinite(v) && v > 0;
}

static int non_negative(stray_real v)
{
	return isfinite(v) && v >= 0;
}

static int map_check(const struct stray_region_map *map,
		     struct stray_error *err)
{
	stray_real sum = 0;
	unsigned r;

	if (map->n < 1 || map->n > STRAY_MAP_REGIONS_MAX)
		return stray_error_set_value(err, STRAY_EINVAL, "map_regions",
			STRAY_MSG("must be 1..64 regions"),
			(stray_real)map->n);
	for (r = 0; r < map->n; r++) {
		if (!non_negative(map->fraction[r]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"map_fraction", STRAY_MSG("must be >= 0"),
				map->fraction[r]);
		if (!non_negative(map->rel_alpha[r]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"map_rel_alpha", STRAY_MSG("must be >= 0"),
				map->rel_alpha[r]);
		sum += map->fraction[r];
	}
	if (stray_fabs(sum - 1) > STRAY_R(1e-6))
		return stray_error_set_value(err, STRAY_EINVAL, "map_fraction",
			STRAY_MSG("fractions must sum to 1"), sum);
	return STRAY_OK;
}

int stray_fdr_model_check(const struct stray_fdr_model *m,
			  struct stray_error *err)
{
	if (!non_negative(m->f_src_ph_s_m2))
		return stray_error_set_value(err, STRAY_EINVAL, "f_src",
			STRAY_MSG("must be finite and >= 0"), m->f_src_ph_s_m2);
	if (!positive(m->f_drs_ph_s_m2))
		return stray_error_set_value(err, STRAY_EINVAL, "f_drs",
			STRAY_MSG("must be finite and > 0"), m->f_drs_ph_s_m2);
	if (!positive(m->t_exp_s))
		return stray_error_set_value(err, STRAY_EINVAL, "t_exp_s",
			STRAY_MSG("must be finite and > 0"), m->t_exp_s);
	if (!positive(m->a_px_m2))
		return stray_error_set_value(err, STRAY_EINVAL, "a_px",
			STRAY_MSG("must be finite and > 0"), m->a_px_m2);
	if (!positive(m->k_px))
		return stray_error_set_value(err, STRAY_EINVAL, "k_px",
			STRAY_MSG("must be finite and > 0"), m->k_px);
	if (!positive(m->a_cs_m2))
		return stray_error_set_value(err, STRAY_EINVAL, "a_cs",
			STRAY_MSG("must be finite and > 0"), m->a_cs_m2);
	if (!(isfinite(m->n_pps) && m->n_pps >= 1))
		return stray_error_set_value(err, STRAY_EINVAL, "n_pps",
			STRAY_MSG("must be >= 1 pixel"), m->n_pps);
	if (!(isfinite(m->n_tot) && m->n_tot >= m->n_pps))
		return stray_error_set_value(err, STRAY_EINVAL, "n_tot",
			STRAY_MSG("must be >= n_pps"), m->n_tot);
	if (!(m->pr_drs > 0 && m->pr_drs < 1))
		return stray_error_set_value(err, STRAY_EINVAL, "pr_drs",
			STRAY_MSG("must lie strictly between 0 and 1"),
			m->pr_drs);
	if (!non_negative(m->read_noise_e))
		return stray_error_set_value(err, STRAY_EINVAL, "read_noise_e",
			STRAY_MSG("must be finite and >= 0"), m->read_noise_e);
	if (!non_negative(m->dark_current_e_s))
		return stray_error_set_value(err, STRAY_EINVAL,
			"dark_current_e_s", STRAY_MSG("must be finite and >= 0"),
			m->dark_current_e_s);
	if (m->noise != STRAY_NOISE_GAUSS &&
	    !(STRAY_WITH_POISSON && m->noise == STRAY_NOISE_POISSON))
		return stray_error_set_value(err, STRAY_EINVAL, "noise_model",
			STRAY_MSG("must be gauss, or poisson where built in"),
			(stray_real)m->noise);
	return m->map ? map_check(m->map, err) : STRAY_OK;
}

stray_real stray_fdr_pixel_photons(const struct stray_fdr_model *m,
				   stray_real alpha)
{
	/* eq. 2.3: I_px = alpha_sys F_src t_exp A_px, times k_px for a
	 * power-ratio alpha (eq. 3.11-3.12; k_px = 1 is the thesis) */
	return alpha * m->f_src_ph_s_m2 * m->t_exp_s * m->a_px_m2 * m->k_px;
}

stray_real stray_fdr_drs_photons(const struct stray_fdr_model *m)
{
	/* eq. 2.12: I_drs = F_drs t_exp A_cs */
	return m->f_drs_ph_s_m2 * m->t_exp_s * m->a_cs_m2;
}

/* Detector-noise variance of one window, b (zero in the thesis model). */
static stray_real window_noise_var(const struct stray_fdr_model *m)
{
	return m->n_pps * (m->read_noise_e * m->read_noise_e +
			   m->dark_current_e_s * m->t_exp_s);
}

/* ln Pr(X >= mean + t) for a window of Poisson mean mu (shifted Poisson). */
static int log_poisson_excess(stray_real mu, stray_real t, stray_real *log_pr,
			      struct stray_error *err)
{
	if (mu <= 0) {
		*log_pr = t > 0 ? -STRAY_HUGE : 0;
		return STRAY_OK;
	}
	if (mu > POISSON_GAUSS_MEAN) {
		*log_pr = stray_log_gauss_q(t / stray_sqrt(mu));
		return STRAY_OK;
	}
	if (mu + t <= 0) {
		*log_pr = 0;
		return STRAY_OK;
	}
	return stray_log_gamma_p(mu + t, mu, log_pr, err);
}

struct drs_ctx {
	const struct stray_fdr_model *m;
	stray_real mu;		/* Poisson mean of star + noise counts */
	stray_real b;
	stray_real log_target;
};

/* Residual of eq. 2.16 in the Poisson model: ln Pr(X >= I) - ln Pr_drs. */
static int drs_residual(stray_real i, void *ctx, stray_real *y)
{
	const struct drs_ctx *c = ctx;
	stray_real log_pr;
	int rc = log_poisson_excess(c->mu, i - (c->mu - c->b), &log_pr, 0);

	*y = log_pr - c->log_target;
	return rc;
}

stray_real stray_fdr_threshold_gauss(const struct stray_fdr_model *m,
				     stray_real z_drs)
{
	/*
	 * eq. 2.13: the DRS count is Gaussian, eq. 2.14: mu_drs = I_drs,
	 * eq. 2.15: sigma^2_drs = I_drs (+ b); eq. 2.16: Pr_drs =
	 * Q((I_sdt - mu_drs) / sigma_drs), solved for I_sdt
	 */
	stray_real i_drs = stray_fdr_drs_photons(m);

	return i_drs + z_drs * stray_sqrt(i_drs + window_noise_var(m));
}

int stray_fdr_threshold(const struct stray_fdr_model *m, stray_real *i_sdt,
			struct stray_error *err)
{
	stray_real i_drs, b, z;
	int rc = stray_fdr_model_check(m, err);

	if (rc != STRAY_OK)
		return rc;
	i_drs = stray_fdr_drs_photons(m);
	b = window_noise_var(m);
	if (!STRAY_WITH_POISSON || m->noise == STRAY_NOISE_GAUSS) {
		rc = stray_gauss_q_inv(m->pr_drs, &z, err);
		if (rc == STRAY_OK)
			*i_sdt = stray_fdr_threshold_gauss(m, z);
		return rc;
	} else {
		struct drs_ctx c = { m, i_drs + b, b, stray_log(m->pr_drs) };
		struct stray_root_result res;
		stray_real span = i_drs + 40 * stray_sqrt(i_drs + b) + 40;

		rc = stray_root_brent(drs_residual, &c, -span, span,
				      STRAY_TOL(1e-9) * span, &res, err);
		if (rc == STRAY_OK)
			*i_sdt = res.x;
		return rc;
	}
}

/* ln Pr_fd of one window whose pixels see attenuation alpha (eq. 2.17). */
int stray_fdr_log_pr_fd(const struct stray_fdr_model *m, stray_real alpha,
			stray_real i_sdt, stray_real *log_pr_fd,
			struct stray_error *err)
{
	/*
	 * eq. 2.4: each pixel Gaussian, eq. 2.5: mu_px = I_px, eq. 2.6:
	 * sigma^2_px = I_px; eq. 2.7: the window sums n_pps of them, and
	 * eq. 2.8: the sum is Gaussian with eq. 2.9: mu_samp = n_pps I_px,
	 * eq. 2.10: sigma^2_samp = n_pps I_px (+ b); eq. 2.11: re-centred on
	 * the mean background, mu_samp = 0
	 */
	stray_real var = m->n_pps * stray_fdr_pixel_photons(m, alpha) +
		     window_noise_var(m);

	if (!non_negative(alpha))
		return stray_error_set_value(err, STRAY_EINVAL, "alpha",
			STRAY_MSG("must be finite and >= 0"), alpha);
	if (STRAY_WITH_POISSON && m->noise == STRAY_NOISE_POISSON)
		return log_poisson_excess(var, i_sdt, log_pr_fd, err);
	if (var <= 0)
		*log_pr_fd = i_sdt > 0 ? -STRAY_HUGE : 0;
	else
		*log_pr_fd = stray_log_gauss_q(i_sdt / stray_sqrt(var));
	return STRAY_OK;
}

/* The map's mean relative attenuation, sum fraction * rel_alpha, by which
 * each region's rel_alpha is divided (so the map keeps the mean alpha). */
int stray_region_map_norm(const struct stray_region_map *map,
			  stray_real *norm, struct stray_error *err)
{
	unsigned r;

	*norm = 0;
	for (r = 0; r < map->n; r++)
		*norm += map->fraction[r] * map->rel_alpha[r];
	if (!(*norm > 0))
		return stray_error_set(err, STRAY_EINVAL, "map_rel_alpha",
			STRAY_MSG("map carries no light"));
	return STRAY_OK;
}

int stray_fdr_log_rate(const struct stray_fdr_model *m, stray_real alpha,
		       stray_real i_sdt, stray_real *log_fdr,
		       struct stray_error *err)
{
	/* eq. 2.18: FDR = n_tot / n_pps * Pr_fd, summed over map regions */
	stray_real log_windows = stray_log(m->n_tot / m->n_pps);
	stray_real acc = -STRAY_HUGE, norm = 0, lp;
	const struct stray_region_map *map = m->map;
	unsigned r;
	int rc;

	if (!map) {
		rc = stray_fdr_log_pr_fd(m, alpha, i_sdt, &lp, err);
		*log_fdr = log_windows + lp;
		return rc;
	}
	if ((rc = stray_region_map_norm(map, &norm, err)) != STRAY_OK)
		return rc;
	for (r = 0; r < map->n; r++) {
		if (map->fraction[r] == 0)
			continue;
		rc = stray_fdr_log_pr_fd(m, alpha * map->rel_alpha[r] / norm,
					 i_sdt, &lp, err);
		if (rc != STRAY_OK)
			return rc;
		acc = stray_log_add(acc, stray_log(map->fraction[r]) + lp);
	}
	*log_fdr = log_windows + acc;
	return STRAY_OK;
}

int stray_fdr_rate(const struct stray_fdr_model *m, stray_real alpha,
		   stray_real *fdr, struct stray_error *err)
{
	stray_real i_sdt, log_fdr;
	int rc = stray_fdr_threshold(m, &i_sdt, err);

	if (rc == STRAY_OK)
		rc = stray_fdr_log_rate(m, alpha, i_sdt, &log_fdr, err);
	if (rc == STRAY_OK)
		*fdr = stray_exp(log_fdr);
	return rc;
}

struct req_ctx {
	const struct stray_fdr_model *m;
	stray_real i_sdt;
	stray_real log_rate;
};

/* ln FDR(e^u) - ln rate: increasing in u, so it brackets one root. */
static int req_residual(stray_real u, void *ctx, stray_real *y)
{
	const struct req_ctx *c = ctx;
	stray_real log_fdr;
	int rc = stray_fdr_log_rate(c->m, stray_exp(u), c->i_sdt, &log_fdr, 0);

	/* The far end can give -inf (no light, no noise): keep it finite. */
	*y = (log_fdr < -STRAY_REAL_MAX ? -STRAY_REAL_MAX : log_fdr) -
	     c->log_rate;
	return rc;
}

int stray_fdr_alpha_required(const struct stray_fdr_model *m,
			     stray_real rate, stray_real *alpha_req,
			     struct stray_error *err)
{
	struct req_ctx c;
	struct stray_root_result res;
	stray_real lo = stray_log(ALPHA_SEARCH_MIN);
	stray_real hi = stray_log(ALPHA_SEARCH_MAX), y;
	int rc;

	if (!positive(rate))
		return stray_error_set_value(err, STRAY_EINVAL, "rate",
			STRAY_MSG("must be finite and > 0"), rate);
	c.m = m;
	c.log_rate = stray_log(rate);
	rc = stray_fdr_threshold(m, &c.i_sdt, err);
	if (rc != STRAY_OK)
		return rc;
	if ((rc = req_residual(lo, &c, &y)) != STRAY_OK)
		return rc;
	if (y > 0)
		return stray_error_set_value(err, STRAY_ERANGE, "rate",
			STRAY_MSG("exceeded by detector noise alone"), rate);
	if ((rc = req_residual(hi, &c, &y)) != STRAY_OK)
		return rc;
	if (y < 0)
		return stray_error_set_value(err, STRAY_ERANGE, "rate",
			STRAY_MSG("not reached even at alpha 1e12"), rate);
	rc = stray_root_brent(req_residual, &c, lo, hi, STRAY_TOL(1e-12), &res,
			      err);
	if (rc == STRAY_OK)
		*alpha_req = stray_exp(res.x);
	return rc;
}
