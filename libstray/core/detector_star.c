/*
 * detector_star.c - the lost-star model (stray/detector.h): the chance
 * that a star of I photo-electrons (eq. 2.12) at a random place is found
 * by each detector under I_px stray photons per pixel (eq. 2.3).  Closed
 * forms in Gaussian pixel noise: a pixel of star signal s has variance
 * s + b, b = I_px + read^2 + dark t (stray_detector_pixel_var); the
 * background is known (subtracted).  Averaged over the star's place in a
 * pixel (SUB x SUB places over a quarter pixel: every detector is
 * symmetric).  Freestanding: no heap, every loop bounded.
 */
#include "stray/detector_blob.h"
#include "stray/detector_pixel.h"
#include "stray/detector_star.h"
#include "stray/tail.h"

#define SUB 4			/* places per axis over [0, 1/2) px */
#define Z_STEPS 160		/* Simpson intervals over z in [-8, 8] */
/* WINDOW: the 21 positions within sqrt(5) px of the star's pixel.  On
 * rendered frames (tests/frames/test_detector_mc.c) the positions within
 * 1 or sqrt(2) px under-predict the detection by 0.06-0.11 at 1e-7; from
 * sqrt(5) px on the prediction no longer changes (sqrt(8): +0.002). */
#define POS_R2 5
/* THRESHOLD: pixels within 2.5 px (within 1.5 or 2 px the prediction
 * falls 0.07-0.16 below the frames at 2e-7). */
#define NEAR_R2 STRAY_R(6.25)
/* TETRA3: the side of its local-mean filter (get_centroids_from_image's
 * filtsize, 25): the star's own light in the box raises the background
 * removed under it by I / 25^2. */
#define TETRA3_FILTSIZE 25
#define G_HALF 70		/* 1-D pixel fractions, |i| <= 64 + 3 */
#define LOG_E_MIN STRAY_R(0)	/* limiting photons searched in 1..1e12 */
#define LOG_E_MAX STRAY_R(27.631)
#define LIMIT_STEPS 80

unsigned stray_detector_positions(int dx[STRAY_DET_POS_MAX],
				  int dy[STRAY_DET_POS_MAX])
{
	unsigned n = 0;
	int x, y;

	for (y = -2; y <= 2; y++)
		for (x = -2; x <= 2; x++)
			if (x * x + y * y <= POS_R2 && n < STRAY_DET_POS_MAX) {
				dx[n] = x;
				dy[n] = y;
				n++;
			}
	return n;
}

static stray_real gauss_cdf(stray_real z)
{
	return STRAY_R(0.5) * stray_erfc(-z * STRAY_R(0.70710678118654752440));
}

/* A pixel of star signal s over background variance b above t. */
static stray_real pixel_above(stray_real s, stray_real b, stray_real t)
{
	stray_real v = s + b;

	return v > 0 ? gauss_cdf((s - t) / stray_sqrt(v)) : (s > t);
}

/* 1-D pixel fractions g[i + G_HALF] of a star at o from pixel 0's centre. */
static void psf_1d(stray_real sigma, stray_real o, stray_real *g, int half)
{
	stray_real k = 1 / (sigma * STRAY_R(1.41421356237309505));
	int i;

	for (i = -half; i <= half; i++)
		g[i + G_HALF] = STRAY_R(0.5) *
			(stray_erfc((i - STRAY_R(0.5) - o) * k) -
			 stray_erfc((i + STRAY_R(0.5) - o) * k));
}

/*
 * WINDOW: the window sum at position d holds I f_d of the star.  The
 * star's shot noise is common to the positions; their background noise
 * (variance n_px b each) is correlated by the windows' overlap, taken as
 * one mean correlation rho among the positions (equicorrelated normals:
 * a common part sqrt(rho) and independent parts sqrt(1 - rho)).  So
 * Pr(miss) = int phi(z) prod_d Phi((t - I f_d - s_c z) / s_i) dz.
 */
static stray_real window_prob(const struct stray_detector *d, stray_real b,
			      stray_real star, stray_real ox, stray_real oy,
			      stray_real i_sdt)
{
	stray_real gx[2 * G_HALF + 1], gy[2 * G_HALF + 1], f[STRAY_DET_POS_MAX];
	stray_real fmax = 0, sb2 = d->win.n_px * b, sc, si, h, sum = 0;
	int dx[STRAY_DET_POS_MAX], dy[STRAY_DET_POS_MAX];
	int ir = (int)d->window_r_px, x, y, k;
	stray_real r2 = d->window_r_px * d->window_r_px;
	unsigned n = stray_detector_positions(dx, dy), p;

	psf_1d(d->psf_sigma_px, ox, gx, ir + 2);
	psf_1d(d->psf_sigma_px, oy, gy, ir + 2);
	for (p = 0; p < n; p++) {
		f[p] = 0;
		for (y = -ir; y <= ir; y++)
			for (x = -ir; x <= ir; x++)
				if ((stray_real)(x * x + y * y) <= r2)
					f[p] += gx[x + dx[p] + G_HALF] *
						gy[y + dy[p] + G_HALF];
		if (f[p] > fmax)
			fmax = f[p];
	}
	sc = stray_sqrt(d->pos_rho * sb2 + star * fmax * fmax);
	si = stray_sqrt((1 - d->pos_rho) * sb2);
	h = STRAY_R(16.0) / Z_STEPS;
	for (k = 0; k <= Z_STEPS; k++) {
		stray_real z = -8 + k * h, w = k == 0 || k == Z_STEPS ? 1 :
			(k & 1 ? 4 : 2);
		stray_real miss = stray_exp(-STRAY_R(0.5) * z * z) *
				  STRAY_R(0.39894228040143267794);

		for (p = 0; p < n && miss > 0; p++) {
			stray_real a = i_sdt - star * f[p] - sc * z;

			miss *= si > 0 ? gauss_cdf(a / si) : (a > 0);
		}
		sum += w * miss;
	}
	sum *= h / 3;
	return sum > 1 ? 0 : 1 - sum;
}

/* THRESHOLD past the animal table (min_px > STRAY_DET_BLOB_PX_MAX): at
 * least min_px of the pixels within 2.5 px of the star above t (a
 * Poisson-binomial count; they touch the star's peak, so they are taken
 * as connected: detector_blob.c's model is exact in that). */
static stray_real threshold_prob(const struct stray_detector *d, stray_real b,
				 stray_real star, stray_real ox, stray_real oy,
				 stray_real t)
{
	stray_real dp[STRAY_CLUSTER_SIZE_MAX + 2], tail = 0;
	unsigned k, c = d->min_px;
	int i, j;

	for (k = 0; k <= c; k++)
		dp[k] = k == 0;
	/* dp[k]: Pr(k above) for k < c; dp[c]: Pr(>= c above) */
	for (j = -3; j <= 3; j++)
		for (i = -3; i <= 3; i++) {
			stray_real ex = i - ox, ey = j - oy, q;

			if (ex * ex + ey * ey > NEAR_R2)
				continue;
			q = pixel_above(star * stray_detector_psf_pixel(
				d->psf_sigma_px, ox, oy, i, j), b, t);
			dp[c] += dp[c - 1] * q;
			for (k = c - 1; k >= 1; k--)
				dp[k] = dp[k] * (1 - q) + dp[k - 1] * q;
			dp[0] *= 1 - q;
		}
	tail = dp[c];
	return tail;
}

/*
 * TETRA3: a star survives the binary opening when some pixel and its four
 * neighbours are all above t; the crosses centred on the 3 x 3 pixels
 * around the star, by inclusion-exclusion over their 511 unions (pixels
 * independent, so each union's chance is the product over its pixels).
 */
static stray_real tetra3_prob(const struct stray_detector *d, stray_real b,
			      stray_real t, stray_real star, stray_real ox,
			      stray_real oy)
{
	static const int arm[5][2] = { { 0, 0 }, { 1, 0 }, { -1, 0 },
				       { 0, 1 }, { 0, -1 } };
	stray_real q[25], p = 0;
	stray_real lift = star / (TETRA3_FILTSIZE * TETRA3_FILTSIZE);
	unsigned long cross[9];
	unsigned s, c, a, i;

	for (i = 0; i < 25; i++) {
		stray_real sig = star * stray_detector_psf_pixel(
			d->psf_sigma_px, ox, oy, (int)(i % 5) - 2,
			(int)(i / 5) - 2);

		/* the pixel's shot noise is its own; the local mean is
		 * lifted by the star */
		q[i] = pixel_above(sig, b, t + lift);
	}
	for (c = 0; c < 9; c++) {
		int cx = (int)(c % 3) - 1, cy = (int)(c / 3) - 1;

		cross[c] = 0;
		for (a = 0; a < 5; a++)
			cross[c] |= 1ul << ((cy + arm[a][1] + 2) * 5 +
					    (cx + arm[a][0] + 2));
	}
	for (s = 1; s < 512; s++) {
		unsigned long u = 0;
		stray_real prod = 1;
		unsigned bits = 0;

		for (c = 0; c < 9; c++)
			if (s & (1u << c)) {
				u |= cross[c];
				bits++;
			}
		for (i = 0; i < 25; i++)
			if (u & (1ul << i))
				prod *= q[i];
		p += bits & 1 ? prod : -prod;
	}
	return p < 0 ? 0 : p > 1 ? 1 : p;
}

/* Detection probability in one region of stray attenuation alpha_r, the
 * background estimate eps e-/px low (detector.c's eq. R). */
static stray_real region_prob(const struct stray_detector *d,
			      const struct stray_fdr_model *m,
			      stray_real alpha_r, stray_real t3,
			      stray_real star, stray_real eps)
{
	stray_real b = stray_detector_pixel_var(m, alpha_r), sum = 0;
	stray_real i_sdt = d->i_sdt_e - d->win.n_px * eps;
	stray_real t = d->pixel_t_e - eps;
	int i, j;

	if (d->kind == STRAY_DET_THESIS) {
		/* eq. 2.16 with the background's variance n_pps I_px added */
		stray_real v = star + m->n_pps * b;

		return v > 0 ? gauss_cdf((star - d->i_sdt_e) / stray_sqrt(v)) :
			       (star > d->i_sdt_e);
	}
	for (j = 0; j < SUB; j++)
		for (i = 0; i < SUB; i++) {
			stray_real ox = (i + STRAY_R(0.5)) / (2 * SUB);
			stray_real oy = (j + STRAY_R(0.5)) / (2 * SUB);

			if (d->kind == STRAY_DET_WINDOW)
				sum += window_prob(d, b, star, ox, oy, i_sdt);
			else if (d->kind == STRAY_DET_THRESHOLD)
				sum += d->n_animal ?
				       stray_detector_blob_prob(d, b, star, ox,
								oy, t) :
				       threshold_prob(d, b, star, ox, oy, t);
			else
				sum += tetra3_prob(d, b, t3, star, ox, oy);
		}
	return sum / (SUB * SUB);
}

int stray_detector_star_prob(const struct stray_detector *d,
			     const struct stray_fdr_model *m, stray_real alpha,
			     stray_real star_e, stray_real *p,
			     struct stray_error *err)
{
	const struct stray_region_map *map = m->map;
	stray_real t3, norm = 0, s, z[STRAY_DET_RESID_NODES];
	stray_real w[STRAY_DET_RESID_NODES];
	unsigned r, n, k;
	int rc;

	if (!(isfinite(alpha) && alpha >= 0))
		return stray_error_set_value(err, STRAY_EINVAL, "alpha",
			STRAY_MSG("must be finite and >= 0"), alpha);
	if (!(isfinite(star_e) && star_e >= 0))
		return stray_error_set_value(err, STRAY_EINVAL, "star_e",
			STRAY_MSG("must be finite and >= 0"), star_e);
	t3 = stray_detector_tetra3_threshold(d, m, alpha);
	n = stray_detector_resid_nodes(d, z, w);
	if (map && (rc = stray_region_map_norm(map, &norm, err)) != STRAY_OK)
		return rc;
	*p = 0;
	for (k = 0; k < n; k++) {	/* detector.c's eq. R */
		if (!map) {
			s = d->bg_resid_rel * stray_fdr_pixel_photons(m, alpha);
			*p += w[k] * region_prob(d, m, alpha, t3, star_e,
						 z[k] * s);
			continue;
		}
		for (r = 0; r < map->n; r++) {
			stray_real a_r = alpha * map->rel_alpha[r] / norm;

			if (!(map->fraction[r] > 0))
				continue;
			s = d->bg_resid_rel * stray_fdr_pixel_photons(m, a_r);
			*p += w[k] * map->fraction[r] * region_prob(d, m, a_r,
				t3, star_e, z[k] * s);
		}
	}
	return STRAY_OK;
}

int stray_detector_limiting_e(const struct stray_detector *d,
			      const struct stray_fdr_model *m,
			      stray_real alpha, stray_real pr,
			      stray_real *star_e, struct stray_error *err)
{
	stray_real lo = LOG_E_MIN, hi = LOG_E_MAX, p;
	int k, rc;

	if (!(pr > 0 && pr < 1))
		return stray_error_set_value(err, STRAY_EINVAL, "pr",
			STRAY_MSG("must lie strictly between 0 and 1"), pr);
	if ((rc = stray_detector_star_prob(d, m, alpha, stray_exp(hi), &p,
					   err)) != STRAY_OK)
		return rc;
	if (p < pr)
		return stray_error_set_value(err, STRAY_ERANGE, "alpha",
			STRAY_MSG("no star up to 1e12 e- is detected"), alpha);
	/* bisection on ln I: the probability rises with the star's photons */
	for (k = 0; k < LIMIT_STEPS && hi - lo > STRAY_TOL(1e-7); k++) {
		stray_real mid = STRAY_R(0.5) * (lo + hi);

		if ((rc = stray_detector_star_prob(d, m, alpha, stray_exp(mid),
						   &p, err)) != STRAY_OK)
			return rc;
		if (p >= pr)
			hi = mid;
		else
			lo = mid;
	}
	*star_e = stray_exp(hi);
	return STRAY_OK;
}
