/*
 * fdr_field.c - the FDR model extended to sliding-window and pixel-
 * cluster star detectors (fdr_field.h).  Freestanding: no heap, no stdio;
 * every loop bounded.
 */
#include "stray/fdr_field.h"
#include "stray/root.h"
#include "stray/tail.h"

#define BLOB_STEPS 400		/* Simpson intervals of the g(u) integral */
#define DISK_R_MAX 64		/* windows up to 129 px across */
#define LOG_SQRT_2PI STRAY_R(0.91893853320467274178)

/* Pixels of the disk of radius r (centre pixel's centre) at offset dx of
 * itself shifted by (dx, dy): both disks contain the pixel. */
static stray_real disk_overlap(int ir, stray_real r2, int dx, int dy)
{
	stray_real n = 0;
	int x, y;

	for (y = -ir; y <= ir; y++)
		for (x = -ir; x <= ir; x++) {
			stray_real a = (stray_real)(x * x + y * y);
			stray_real bx = (stray_real)(x - dx), by = (stray_real)(y - dy);

			if (a <= r2 && bx * bx + by * by <= r2)
				n += 1;
		}
	return n;
}

int stray_window_disk_corr(stray_real r_px, struct stray_window_corr *c,
			   struct stray_error *err)
{
	static const int off[4][2] = { { -1, 0 }, { -1, -1 }, { 0, -1 },
				       { 1, -1 } };
	stray_real r2 = r_px * r_px;
	int ir, i;

	if (!(r_px >= 1 && r_px <= DISK_R_MAX))
		return stray_error_set_value(err, STRAY_EINVAL, "window_radius_px",
			STRAY_MSG("must lie in 1..64"), r_px);
	ir = (int)r_px;
	c->n_px = disk_overlap(ir, r2, 0, 0);
	for (i = 0; i < 4; i++)
		c->rho[i] = disk_overlap(ir, r2, off[i][0], off[i][1]) / c->n_px;
	return STRAY_OK;
}

/* Phi(z) = 1 - Q(z), the standard normal CDF. */
static stray_real gauss_cdf(stray_real z)
{
	return STRAY_R(0.5) * stray_erfc(-z * STRAY_R(0.70710678118654752440));
}

/* phi(u + t) / phi(u) times the chance all scanned neighbours lie below u. */
static stray_real blob_integrand(const struct stray_window_corr *c,
				 stray_real u, stray_real t)
{
	stray_real x = u + t, f = stray_exp(-u * t - STRAY_R(0.5) * t * t);
	int i;

	for (i = 0; i < 4; i++) {
		stray_real r = c->rho[i], s = stray_sqrt(1 - r * r);

		f *= s > 0 ? gauss_cdf((u - r * x) / s) : (r * x < u);
	}
	return f;
}

int stray_fdr_blob_factor(const struct stray_window_corr *c, stray_real u,
			  stray_real *g, struct stray_error *err)
{
	stray_real span, h, sum, mills;
	int k;

	if (!isfinite(u))
		return stray_error_set_value(err, STRAY_EINVAL, "u",
			STRAY_MSG("must be finite"), u);
	/* phi(u + t)/phi(u) falls as exp(-u t - t^2/2): cover 30 e-folds. */
	span = u > 1 ? STRAY_R(30) / u : STRAY_R(8);
	if (span > 8)
		span = 8;
	h = span / BLOB_STEPS;
	sum = blob_integrand(c, u, 0) + blob_integrand(c, u, span);
	for (k = 1; k < BLOB_STEPS; k++)
		sum += (k & 1 ? 4 : 2) * blob_integrand(c, u, k * h);
	sum *= h / 3;
	/* Mills ratio Q(u)/phi(u), from the log tail (no underflow). */
	mills = stray_exp(stray_log_gauss_q(u) + STRAY_R(0.5) * u * u +
			  LOG_SQRT_2PI);
	*g = sum / mills;
	if (*g > 1)
		*g = 1;
	if (*g < 1 / c->n_px)	/* a blob never exceeds the window */
		*g = 1 / c->n_px;
	return STRAY_OK;
}

/* ln(Pr_fd g) of one region of mean attenuation alpha (eq. 2.17 x g). */
static int region_term(const struct stray_fdr_model *m,
		       const struct stray_window_corr *c, stray_real alpha,
		       stray_real i_sdt, stray_real *lt, struct stray_error *err)
{
	/* eq. 2.9-2.11: window variance n_pps I_px plus detector noise */
	stray_real var = m->n_pps * stray_fdr_pixel_photons(m, alpha) +
		m->n_pps * (m->read_noise_e * m->read_noise_e +
			    m->dark_current_e_s * m->t_exp_s);
	stray_real lp, g = 1;
	int rc = stray_fdr_log_pr_fd(m, alpha, i_sdt, &lp, err);

	if (rc == STRAY_OK && var > 0)
		rc = stray_fdr_blob_factor(c, i_sdt / stray_sqrt(var), &g, err);
	*lt = lp + stray_log(g);
	return rc;
}

int stray_fdr_log_rate_sliding(const struct stray_fdr_model *m,
			       const struct stray_window_corr *c,
			       stray_real alpha, stray_real i_sdt,
			       stray_real *log_fdr, struct stray_error *err)
{
	const struct stray_region_map *map = m->map;
	stray_real acc = -STRAY_HUGE, norm = 0, lt;
	unsigned r;
	int rc;

	if (!map) {
		rc = region_term(m, c, alpha, i_sdt, &lt, err);
		*log_fdr = stray_log(m->n_tot) + lt;
		return rc;
	}
	if ((rc = stray_region_map_norm(map, &norm, err)) != STRAY_OK)
		return rc;
	for (r = 0; r < map->n; r++) {
		if (map->fraction[r] == 0)
			continue;
		rc = region_term(m, c, alpha * map->rel_alpha[r] / norm, i_sdt,
				 &lt, err);
		if (rc != STRAY_OK)
			return rc;
		acc = stray_log_add(acc, stray_log(map->fraction[r]) + lt);
	}
	*log_fdr = stray_log(m->n_tot) + acc;
	return STRAY_OK;
}

stray_real stray_polyplets_fixed(unsigned s)
{
	/* Counted by Redelmeier's enumeration (1981, Discrete Math. 36, 191);
	 * s <= 7 re-derived by the enumeration in
	 * tests/frames/test_fdr_field.c. */
	static const stray_real a[STRAY_CLUSTER_SIZE_MAX + 1] = {
		0, 1, 4, 20, 110, 638, 3832, 23592, 147941, 940982,
		6053180
	};

	return s <= STRAY_CLUSTER_SIZE_MAX ? a[s] : 0;
}

/* Mean 8-neighbour perimeter of the fixed polyplets of s cells (the same
 * enumeration; 2.57 cells more per cell past s = 7). */
static stray_real polyplet_perimeter(unsigned s)
{
	static const stray_real b[8] = {
		0, 8, 11, 13.8, 16.482, 19.11, 21.704, 24.274
	};

	return s < 8 ? b[s] : b[7] + STRAY_R(2.57) * (stray_real)(s - 7);
}

/* Past this mean the pixel tail is Gaussian: a cluster threshold is a
 * few sigma, where the skew error z^3 / (6 sqrt(mu)) is < 1e-3 (fdr.c's
 * POISSON_GAUSS_MEAN, same reasoning). */
#define CLUSTER_GAUSS_MEAN STRAY_R(1e8)

int stray_fdr_log_rate_clusters(stray_real n_px, stray_real mu_e,
				stray_real var_e, stray_real t_e,
				unsigned min_px, stray_real *log_fdr,
				struct stray_error *err)
{
	stray_real lp, lq, acc = -STRAY_HUGE, mu = mu_e + var_e;
	unsigned s;
	int rc;

	if (!(n_px > 0) || !(mu > 0) || !(min_px >= 1) ||
	    min_px > STRAY_CLUSTER_SIZE_MAX)
		return stray_error_set_value(err, STRAY_EINVAL, "cluster_model",
			STRAY_MSG("needs pixels, noise and 1..10 px clusters"),
			(stray_real)min_px);
	/* Pixel exceedance p: shifted Poisson Pr(X >= mu + t), as fdr.c.
	 * With Gaussian noise of sigma >= 0.5 the count is continuous, and
	 * the lattice tail Pr(N >= a) of the gamma function stands for it
	 * half a count higher (the continuity correction): at single-pixel
	 * thresholds of ~2 sigma that is 5 % in p, 30 % in p^5. */
	stray_real a = mu + t_e + (var_e >= STRAY_R(0.25) ? STRAY_R(0.5) : 0);

	if (a <= 0) {
		lp = 0;
		rc = STRAY_OK;
	} else if (mu > CLUSTER_GAUSS_MEAN) {
		/* the series would need > 1e5 terms ("did not converge" at
		 * alpha 0.1): the Gaussian limit, as fdr.c does past 1e8 */
		lp = stray_log_gauss_q((a - mu) / stray_sqrt(mu));
		rc = STRAY_OK;
	} else {
		rc = stray_log_gamma_p(a, mu, &lp, err);
	}
	if (rc != STRAY_OK)
		return rc;
	lq = lp < -30 ? -stray_exp(lp) : stray_log(1 - stray_exp(lp));
	for (s = min_px; s <= STRAY_CLUSTER_SIZE_MAX; s++)
		acc = stray_log_add(acc, stray_log(stray_polyplets_fixed(s)) +
				    s * lp + polyplet_perimeter(s) * lq);
	*log_fdr = stray_log(n_px) + acc;
	return STRAY_OK;
}

struct sliding_ctx {
	const struct stray_fdr_model *m;
	const struct stray_window_corr *c;
	stray_real i_sdt, log_rate;
};

/* ln rate_sliding(e^u) - ln rate: increasing in u. */
static int sliding_residual(stray_real u, void *ctx, stray_real *y)
{
	const struct sliding_ctx *s = ctx;
	stray_real lf;
	int rc = stray_fdr_log_rate_sliding(s->m, s->c, stray_exp(u), s->i_sdt,
					    &lf, 0);

	*y = (lf < -STRAY_REAL_MAX ? -STRAY_REAL_MAX : lf) - s->log_rate;
	return rc;
}

int stray_fdr_alpha_required_sliding(const struct stray_fdr_model *m,
				     const struct stray_window_corr *c,
				     stray_real i_sdt, stray_real rate,
				     stray_real *alpha_req,
				     struct stray_error *err)
{
	struct sliding_ctx s;
	struct stray_root_result res;
	stray_real lo = stray_log(STRAY_R(1e-30)), hi = stray_log(STRAY_R(1e12));
	stray_real ylo, yhi;
	int rc;

	if (!(isfinite(rate) && rate > 0))
		return stray_error_set_value(err, STRAY_EINVAL, "rate",
			STRAY_MSG("must be finite and > 0"), rate);
	s.m = m;
	s.c = c;
	s.i_sdt = i_sdt;
	s.log_rate = stray_log(rate);
	if ((rc = sliding_residual(lo, &s, &ylo)) != STRAY_OK ||
	    (rc = sliding_residual(hi, &s, &yhi)) != STRAY_OK)
		return rc;
	if (ylo > 0 || yhi < 0)
		return stray_error_set_value(err, STRAY_ERANGE, "rate",
			STRAY_MSG("not reached for alpha in 1e-30..1e12"), rate);
	rc = stray_root_brent(sliding_residual, &s, lo, hi, STRAY_TOL(1e-12),
			      &res, err);
	if (rc == STRAY_OK)
		*alpha_req = stray_exp(res.x);
	return rc;
}
