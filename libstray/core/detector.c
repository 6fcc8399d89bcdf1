/*
 * detector.c - named star detectors: names, thresholds, false stars per
 * image and the attenuation both failure modes allow (stray/detector.h).
 * Freestanding: no heap, no stdio, every loop bounded.  The lost-star
 * model (a star's detection probability) is in detector_star.c.
 */
#include "stray/detector.h"
#include "stray/root.h"
#include "stray/tail.h"

#define LOG_ALPHA_MIN STRAY_R(-69.0776)	/* ln 1e-30 */
#define LOG_ALPHA_MAX STRAY_R(27.631)		/* ln 1e12 */
#define PSF_PER_RADIUS STRAY_R(0.25)
#define DISK_HALF 64		/* fdr_field.h: windows up to r = 64 */
#define PSF_HALF 4		/* the DRS's brightest pixels lie within */
/* Past this pixel mean the Poisson tail is a Gaussian's (fdr.c's
 * POISSON_GAUSS_MEAN): the incomplete gamma function would need > 1e5
 * terms, and skew is below 1e-9. */
#define PIXEL_GAUSS_MEAN STRAY_R(1e8)

static const char *const names[STRAY_DET_COUNT] = {
	"thesis", "window", "threshold", "tetra3"
};

const char *stray_detector_name(enum stray_detector_kind k)
{
	return (unsigned)k < STRAY_DET_COUNT ? names[k] : 0;
}

const char *stray_failure_mode_name(enum stray_failure_mode f)
{
	return f == STRAY_FAIL_LOST_STARS ? "lost_stars" : "false_stars";
}

/* strcmp, which a freestanding build does not have; bounded. */
static int same_name(const char *a, const char *b)
{
	unsigned i;

	for (i = 0; i < 64; i++) {
		if (a[i] != b[i])
			return 0;
		if (!a[i])
			return 1;
	}
	return 0;
}

int stray_detector_parse(const char *name, enum stray_detector_kind *k,
			 struct stray_error *err)
{
	unsigned i;

	for (i = 0; name && i < STRAY_DET_COUNT; i++)
		if (same_name(name, names[i])) {
			*k = (enum stray_detector_kind)i;
			return STRAY_OK;
		}
	return stray_error_set(err, STRAY_EINVAL, "detector",
		STRAY_MSG("must be thesis, window, threshold or tetra3"));
}

void stray_detector_init(struct stray_detector *d,
			 enum stray_detector_kind kind, stray_real n_pps)
{
	stray_real r = (stray_real)(int)(stray_sqrt(n_pps /
				STRAY_R(3.14159265358979)) + STRAY_R(0.5));

	d->kind = kind;
	d->sigma_k = 3;
	d->min_px = 5;
	d->window_r_px = r < 1 ? 1 : r;
	d->psf_sigma_px = d->window_r_px * PSF_PER_RADIUS;
	d->i_sdt_e = d->pixel_t_e = d->pos_rho = d->bg_resid_rel = 0;
	d->win.n_px = 0;
	d->n_animal = 0;
}

/* The fraction in the n-th brightest pixel of a star centred on a pixel. */
static stray_real nth_pixel_fraction(stray_real s, unsigned n)
{
	enum { W = 2 * PSF_HALF + 1 };
	stray_real f[W * W], t;
	unsigned i, j, c = 0;

	for (j = 0; j < W; j++)
		for (i = 0; i < W; i++)
			f[c++] = stray_detector_psf_pixel(s, 0, 0,
				(int)i - PSF_HALF, (int)j - PSF_HALF);
	for (i = 0; i < n && i < W * W; i++)	/* partial selection sort */
		for (j = i + 1; j < W * W; j++)
			if (f[j] > f[i]) {
				t = f[i];
				f[i] = f[j];
				f[j] = t;
			}
	return f[n - 1];
}

/* Pixels of the radius-r disk window that its copy shifted by (dx, dy)
 * also covers. */
static stray_real disk_overlap(stray_real r, int dx, int dy)
{
	int ir = (int)r, x, y;
	stray_real n = 0, r2 = r * r;

	for (y = -ir; y <= ir; y++)
		for (x = -ir; x <= ir; x++) {
			stray_real bx = (stray_real)(x - dx);
			stray_real by = (stray_real)(y - dy);

			if ((stray_real)(x * x + y * y) <= r2 &&
			    bx * bx + by * by <= r2)
				n += 1;
		}
	return n;
}

/* The window positions near a star (stray_detector_positions) and the
 * mean overlap of every pair of them, the correlation of their noise. */
static stray_real positions_rho(stray_real r)
{
	int dx[STRAY_DET_POS_MAX], dy[STRAY_DET_POS_MAX];
	unsigned n = stray_detector_positions(dx, dy), i, j, pairs = 0;
	stray_real sum = 0, n_px = disk_overlap(r, 0, 0);

	for (i = 0; i < n; i++)
		for (j = i + 1; j < n; j++) {
			sum += disk_overlap(r, dx[i] - dx[j], dy[i] - dy[j]);
			pairs++;
		}
	return pairs ? sum / (pairs * n_px) : 1;
}

int stray_detector_setup(struct stray_detector *d,
			 const struct stray_fdr_model *m,
			 struct stray_error *err)
{
	struct stray_fdr_model g = *m;
	stray_real z, f, i_drs, var0;
	int rc;

	if ((unsigned)d->kind >= STRAY_DET_COUNT)
		return stray_error_set_value(err, STRAY_EINVAL, "detector",
			STRAY_MSG("unknown detector"), (stray_real)d->kind);
	if (!(isfinite(d->sigma_k) && d->sigma_k >= STRAY_R(0.5) &&
	      d->sigma_k <= 20))
		return stray_error_set_value(err, STRAY_EINVAL, "detector_sigma",
			STRAY_MSG("must lie in 0.5..20"), d->sigma_k);
	if (d->min_px < 1 || d->min_px > STRAY_CLUSTER_SIZE_MAX)
		return stray_error_set_value(err, STRAY_EINVAL, "detector_min_px",
			STRAY_MSG("must lie in 1..10"), (stray_real)d->min_px);
	if (!(d->window_r_px >= 1 && d->window_r_px <= DISK_HALF))
		return stray_error_set_value(err, STRAY_EINVAL, "window_radius_px",
			STRAY_MSG("must lie in 1..64"), d->window_r_px);
	if (!(isfinite(d->bg_resid_rel) && d->bg_resid_rel >= 0 &&
	      d->bg_resid_rel <= 1))
		return stray_error_set_value(err, STRAY_EINVAL, "bg_resid_rel",
			STRAY_MSG("must lie in 0..1"), d->bg_resid_rel);
	if (!(d->psf_sigma_px >= STRAY_R(0.25) && d->psf_sigma_px <= 16))
		return stray_error_set_value(err, STRAY_EINVAL, "psf_sigma_px",
			STRAY_MSG("must lie in 0.25..16"), d->psf_sigma_px);
	if ((rc = stray_fdr_model_check(m, err)) != STRAY_OK)
		return rc;
	if (d->kind == STRAY_DET_THESIS)
		return stray_fdr_threshold(m, &d->i_sdt_e, err);
	/* eq. 2.16 for the real detectors with the Gaussian DRS (as stray
	 * frames sets them), whatever tails the false stars use */
	g.noise = STRAY_NOISE_GAUSS;
	g.map = 0;
	if ((rc = stray_fdr_threshold(&g, &d->i_sdt_e, err)) != STRAY_OK ||
	    (rc = stray_window_disk_corr(d->window_r_px, &d->win, err)) !=
		    STRAY_OK ||
	    (rc = stray_gauss_q_inv(m->pr_drs, &z, err)) != STRAY_OK)
		return rc;
	d->pos_rho = positions_rho(d->window_r_px);
	if ((rc = stray_detector_blob_setup(d, err)) != STRAY_OK)
		return rc;
	/* The fixed pixel threshold's eq. 2.16: the DRS centred on a pixel
	 * lights its min_px-th brightest pixel above it with Pr_drs. */
	i_drs = stray_fdr_drs_photons(m);
	f = nth_pixel_fraction(d->psf_sigma_px, d->min_px);
	var0 = stray_detector_pixel_var(m, 0);
	d->pixel_t_e = f * i_drs + z * stray_sqrt(f * i_drs + var0);
	return STRAY_OK;
}

/* ln Pr(count > mean + t) of a pixel: Poisson mean mu_e plus Gaussian
 * noise var_e (shifted Poisson with the continuity correction, as
 * stray_fdr_log_rate_clusters). */
static int log_pixel_exceed(stray_real mu_e, stray_real var_e, stray_real t_e,
			    stray_real *lp, struct stray_error *err)
{
	stray_real mu = mu_e + var_e;
	stray_real a = mu + t_e + (var_e >= STRAY_R(0.25) ? STRAY_R(0.5) : 0);

	if (!(mu > 0)) {
		*lp = t_e < 0 ? 0 : -STRAY_HUGE;
		return STRAY_OK;
	}
	if (a <= 0) {
		*lp = 0;
		return STRAY_OK;
	}
	if (mu > PIXEL_GAUSS_MEAN) {
		*lp = stray_log_gauss_q(t_e / stray_sqrt(mu));
		return STRAY_OK;
	}
	return stray_log_gamma_p(a, mu, lp, err);
}

/* One region's ln false stars of a pixel detector, n_px pixels at mean
 * stray photons i_px, threshold t_e above the mean. */
static int region_pixel_rate(const struct stray_detector *d,
			     const struct stray_fdr_model *m, stray_real n_px,
			     stray_real i_px, stray_real t_e, stray_real *lr,
			     struct stray_error *err)
{
	stray_real var = m->read_noise_e * m->read_noise_e, lp;
	stray_real mu = i_px + m->dark_current_e_s * m->t_exp_s;
	int rc;

	if (d->kind == STRAY_DET_THRESHOLD) {
		if (!(mu + var > 0)) {
			*lr = -STRAY_HUGE;
			return STRAY_OK;
		}
		/* far past any tolerated rate the pixel exceedance is ~1/2 and
		 * the rate has saturated: hold it at PIXEL_GAUSS_MEAN */
		if (mu + var > PIXEL_GAUSS_MEAN)
			mu = PIXEL_GAUSS_MEAN - var;
		return stray_fdr_log_rate_clusters(n_px, mu, var, t_e,
						   d->min_px, lr, err);
	}
	/* TETRA3: the binary opening keeps a blob only where a pixel and its
	 * four neighbours are all above; isolated crosses are the leading
	 * term of the opened blobs at small p (5 pixels, p^5). */
	if ((rc = log_pixel_exceed(mu, var, t_e, &lp, err)) != STRAY_OK)
		return rc;
	*lr = stray_log(n_px) + 5 * lp;
	return STRAY_OK;
}

/* One region's ln false stars: n_px pixels at mean stray photons i_px,
 * the background estimate low by z bg_resid_rel i_px (eq. R below). */
static int region_rate(const struct stray_detector *d,
		       const struct stray_fdr_model *m, stray_real n_px,
		       stray_real alpha_r, stray_real t3, stray_real z,
		       stray_real *lr, struct stray_error *err)
{
	stray_real i_px = stray_fdr_pixel_photons(m, alpha_r);
	stray_real eps = z * d->bg_resid_rel * i_px;

	if (d->kind == STRAY_DET_WINDOW) {
		struct stray_fdr_model g = *m;
		stray_real u = d->i_sdt_e - d->win.n_px * eps;

		g.map = 0;
		g.n_tot = n_px;
		/* a node whose threshold falls to the background is held
		 * there: the rate has saturated (every window a blob) */
		return stray_fdr_log_rate_sliding(&g, &d->win, alpha_r,
						  u > 0 ? u : 0, lr, err);
	}
	if (d->kind == STRAY_DET_THRESHOLD)
		t3 = d->pixel_t_e - (eps < d->pixel_t_e ? eps : d->pixel_t_e);
	return region_pixel_rate(d, m, n_px, i_px, t3, lr, err);
}

/* ln false stars over the map's regions (or uniform light) at node z. */
static int map_false_rate(const struct stray_detector *d,
			  const struct stray_fdr_model *m, stray_real alpha,
			  stray_real z, stray_real *log_rate,
			  struct stray_error *err)
{
	const struct stray_region_map *map = m->map;
	stray_real t3 = d->kind == STRAY_DET_TETRA3 ?
		stray_detector_tetra3_threshold(d, m, alpha) : 0;
	stray_real norm = 0, acc = -STRAY_HUGE, lr;
	unsigned r;
	int rc;

	if (!map)
		return region_rate(d, m, m->n_tot, alpha, t3, z, log_rate, err);
	if ((rc = stray_region_map_norm(map, &norm, err)) != STRAY_OK)
		return rc;
	for (r = 0; r < map->n; r++) {
		if (map->fraction[r] <= 0)
			continue;
		rc = region_rate(d, m, m->n_tot * map->fraction[r],
				 alpha * map->rel_alpha[r] / norm, t3, z, &lr,
				 err);
		if (rc != STRAY_OK)
			return rc;
		acc = stray_log_add(acc, lr);
	}
	*log_rate = acc;
	return STRAY_OK;
}

/*
 * The background-error term (issue 28: mapped light).  A detector that
 * subtracts an estimate b^ of the background leaves e = L - b^ in every
 * pixel where the stray light's shape has structure its estimator cannot
 * follow (curvature, steps at the tile scale).  e varies slowly, so a
 * window sum carries n_px e and a star's pixels share one e: over the
 * frame the rate and the detection probability are their averages over
 * the distribution of e, taken as N(0, s^2), s = bg_resid_rel I_px with
 * I_px the region's level (the map's structure multiplies its light):
 *
 *   rate = sum_k w_k rate(t - z_k s),   P = sum_k w_k P(t - z_k s)     (R)
 *
 * (Gauss-Hermite nodes z_k, weights w_k of N(0, 1); t the pixel threshold,
 * or I_sdt with n_px z_k s for the window sum).  Convex in e, so structure
 * adds false stars and, for a star near its limit, takes few.
 */
int stray_detector_log_false_rate(const struct stray_detector *d,
				  const struct stray_fdr_model *m,
				  stray_real alpha, stray_real *log_rate,
				  struct stray_error *err)
{
	stray_real z[STRAY_DET_RESID_NODES], w[STRAY_DET_RESID_NODES];
	stray_real acc = -STRAY_HUGE, lr;
	unsigned n, k;
	int rc;

	if (!(isfinite(alpha) && alpha >= 0))
		return stray_error_set_value(err, STRAY_EINVAL, "alpha",
			STRAY_MSG("must be finite and >= 0"), alpha);
	if (d->kind == STRAY_DET_THESIS)
		return stray_fdr_log_rate(m, alpha, d->i_sdt_e, log_rate, err);
	if (d->kind == STRAY_DET_WINDOW && !(d->bg_resid_rel > 0))
		return stray_fdr_log_rate_sliding(m, &d->win, alpha, d->i_sdt_e,
						  log_rate, err);
	n = stray_detector_resid_nodes(d, z, w);
	for (k = 0; k < n; k++) {	/* eq. R */
		if ((rc = map_false_rate(d, m, alpha, z[k], &lr, err)) !=
		    STRAY_OK)
			return rc;
		acc = n == 1 ? lr : stray_log_add(acc, stray_log(w[k]) + lr);
	}
	*log_rate = acc;
	return STRAY_OK;
}

struct search_ctx {
	const struct stray_detector *d;
	const struct stray_fdr_model *m;
	stray_real target;
	int lost;		/* 0: ln false rate, 1: DRS probability */
};

/* Increasing in u = ln alpha: ln rate - ln target, or target - P_drs. */
static int search_fn(stray_real u, void *ctx, stray_real *y)
{
	const struct search_ctx *c = ctx;
	stray_real v;
	int rc;

	if (c->lost) {
		rc = stray_detector_star_prob(c->d, c->m, stray_exp(u),
			stray_fdr_drs_photons(c->m), &v, 0);
		*y = c->target - v;
		return rc;
	}
	rc = stray_detector_log_false_rate(c->d, c->m, stray_exp(u), &v, 0);
	if (v < -STRAY_REAL_MAX)
		v = -STRAY_REAL_MAX;
	*y = v - c->target;
	return rc;
}

/* alpha where the increasing search_fn crosses 0: 0 when it is above at
 * 1e-30, +inf when still below at 1e12. */
static int search_alpha(struct search_ctx *c, stray_real *alpha,
			struct stray_error *err)
{
	struct stray_root_result res;
	stray_real ylo, yhi;
	int rc;

	if ((rc = search_fn(LOG_ALPHA_MIN, c, &ylo)) != STRAY_OK ||
	    (rc = search_fn(LOG_ALPHA_MAX, c, &yhi)) != STRAY_OK)
		return stray_error_set(err, rc, "alpha",
			STRAY_MSG("model failed at the search's ends"));
	if (ylo > 0) {
		*alpha = 0;
		return STRAY_OK;
	}
	if (yhi < 0) {
		*alpha = STRAY_HUGE;
		return STRAY_OK;
	}
	rc = stray_root_brent(search_fn, c, LOG_ALPHA_MIN, LOG_ALPHA_MAX,
			      STRAY_TOL(1e-9), &res, err);
	if (rc == STRAY_OK)
		*alpha = stray_exp(res.x);
	return rc;
}

int stray_detector_alpha_required(const struct stray_detector *d,
				  const struct stray_fdr_model *m,
				  stray_real rate, stray_real pr_min,
				  struct stray_detector_req *r,
				  struct stray_error *err)
{
	struct search_ctx c = { d, m, 0, 0 };
	int rc;

	if (!(isfinite(rate) && rate > 0))
		return stray_error_set_value(err, STRAY_EINVAL, "rate",
			STRAY_MSG("must be finite and > 0"), rate);
	if (!(pr_min > 0 && pr_min < 1))
		return stray_error_set_value(err, STRAY_EINVAL, "pr_min",
			STRAY_MSG("must lie strictly between 0 and 1"), pr_min);
	if (d->kind == STRAY_DET_THESIS)	/* as published, eq. 2.18 */
		rc = stray_fdr_alpha_required(m, rate, &r->alpha_false, err);
	else {
		c.target = stray_log(rate);
		rc = search_alpha(&c, &r->alpha_false, err);
	}
	if (rc != STRAY_OK)
		return rc;
	c.target = pr_min;
	c.lost = 1;
	if ((rc = search_alpha(&c, &r->alpha_lost, err)) != STRAY_OK)
		return rc;
	r->binding = d->kind != STRAY_DET_THESIS &&
		     r->alpha_lost < r->alpha_false ?
		STRAY_FAIL_LOST_STARS : STRAY_FAIL_FALSE_STARS;
	r->alpha_req = r->binding == STRAY_FAIL_LOST_STARS ?
		r->alpha_lost : r->alpha_false;
	if (r->alpha_req >= STRAY_HUGE)
		return stray_error_set_value(err, STRAY_ERANGE, "rate",
			STRAY_MSG("neither false stars nor lost stars bind for alpha up to 1e12"),
			rate);
	if (!(r->alpha_req > 0))
		/* the sensor asks what its detector cannot give: bad input */
		return stray_error_set_value(err, STRAY_EINVAL, "pr_drs",
			STRAY_MSG("the reference star is missed even in the dark"),
			pr_min);
	return STRAY_OK;
}
