/*
 * frames_run.c - models, matching and diagnosis of `stray frames`
 * (frames_run.h).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frames/frames_run.h"
#include "stray/sensor.h"
#include "stray/tail.h"

#define MIN_PX 5		/* tetra3's default minimum star area */

/* Photons of a star centred on a pixel in its k-th brightest pixel. */
static double drs_pixel_fraction(double sigma, int k)
{
	enum { H = 4 };
	double g[2 * H + 1], f[(2 * H + 1) * (2 * H + 1)];
	int i, j, n = 0;

	for (i = -H; i <= H; i++)
		g[i + H] = 0.5 * (erf((i + 0.5) / (sigma * sqrt(2.0))) -
				  erf((i - 0.5) / (sigma * sqrt(2.0))));
	for (j = 0; j <= 2 * H; j++)
		for (i = 0; i <= 2 * H; i++)
			f[n++] = g[i] * g[j];
	for (i = 0; i < k; i++)		/* partial selection sort */
		for (j = i + 1; j < n; j++)
			if (f[j] > f[i]) {
				double t = f[i];
				f[i] = f[j];
				f[j] = t;
			}
	return f[k - 1];
}

int frames_model_init(struct frames_model *fm, const struct stray_sensor *s,
		      double f_src, double f_drs, double k_px, double alpha,
		      int cols, int rows, const struct stray_region_map *map,
		      struct stray_error *err)
{
	struct stray_fdr_model g;
	double z, r, i_drs, f_m, var0;
	int rc;

	memset(fm, 0, sizeof(*fm));
	fm->cols = cols;
	fm->rows = rows;
	stray_sensor_fdr_model(s, f_src, f_drs, &fm->m);
	fm->m.n_tot = (double)cols * rows;	/* per rendered frame */
	fm->quant_var_e = STRAY_FRAMES_GAIN_E_PER_DN *
			  STRAY_FRAMES_GAIN_E_PER_DN / 12.0;
	fm->read_noise_e = s->read_noise_e;
	fm->dark_e = s->dark_current_e_s * s->t_exp_s;
	/* Detector noise: read noise with the ADC's quantisation folded in. */
	fm->m.read_noise_e = sqrt(s->read_noise_e * s->read_noise_e +
				  fm->quant_var_e);
	fm->m.dark_current_e_s = s->dark_current_e_s;
	fm->m.noise = STRAY_NOISE_POISSON;
	fm->m.map = map;
	/* k_px is folded into alpha_eff (the model's eq. 2.3 units, as
	 * stray/fdr_field.h takes it): the model's own factor is 1, or
	 * k_px would count twice */
	fm->m.k_px = 1.0;
	fm->alpha_eff = k_px * alpha;
	fm->stray_e = stray_fdr_pixel_photons(&fm->m, fm->alpha_eff);
	g = fm->m;
	g.noise = STRAY_NOISE_GAUSS;
	if ((rc = stray_fdr_threshold(&g, &fm->i_sdt_e, err)) != STRAY_OK)
		return rc;
	r = floor(sqrt(s->star_window_px / 3.14159265358979) + 0.5);
	if ((rc = stray_window_disk_corr(r, &fm->win, err)) != STRAY_OK ||
	    (rc = stray_gauss_q_inv(s->pr_drs, &z, err)) != STRAY_OK)
		return rc;
	/* The threshold detector's eq. 2.16: the DRS, centred on a pixel,
	 * lights its MIN_PX-th brightest pixel above the threshold with
	 * probability Pr_drs. */
	fm->min_px = MIN_PX;
	i_drs = stray_fdr_drs_photons(&fm->m);
	f_m = drs_pixel_fraction(r * STRAY_FRAMES_PSF_PER_RADIUS, MIN_PX);
	var0 = fm->m.read_noise_e * fm->m.read_noise_e + fm->dark_e;
	fm->pixel_threshold_e = f_m * i_drs + z * sqrt(f_m * i_drs + var0);
	return STRAY_OK;
}

/* The pixel-cluster model over the map's regions (or uniform light). */
static int cluster_rate(const struct frames_model *fm, double *rate,
			struct stray_error *err)
{
	const struct stray_region_map *map = fm->m.map;
	double var = fm->m.read_noise_e * fm->m.read_noise_e, n = fm->m.n_tot;
	double lf, norm = 0.0;
	unsigned i;
	int rc;

	*rate = 0.0;
	/* The ADC's 2 e- steps enter as their variance g^2/12 (in var): the
	 * background a detector subtracts wanders across step edges (tile
	 * noise, faint stars, any real unevenness), so the threshold's place
	 * on the steps averages out.  With perfectly flat light and no stars
	 * it does not, and the rate then swings by up to 3x between levels. */
	if (!map) {
		rc = stray_fdr_log_rate_clusters(n, fm->stray_e + fm->dark_e, var,
			fm->pixel_threshold_e, (unsigned)fm->min_px, &lf, err);
		*rate = exp(lf);
		return rc;
	}
	for (i = 0; i < map->n; i++)
		norm += map->fraction[i] * map->rel_alpha[i];
	for (i = 0; i < map->n; i++) {
		if (map->fraction[i] <= 0.0)
			continue;
		rc = stray_fdr_log_rate_clusters(n * map->fraction[i],
			fm->stray_e * map->rel_alpha[i] / norm + fm->dark_e, var,
			fm->pixel_threshold_e, (unsigned)fm->min_px, &lf, err);
		if (rc != STRAY_OK)
			return rc;
		*rate += exp(lf);
	}
	return STRAY_OK;
}

int frames_model_rates(const struct frames_model *fm,
		       struct frames_rates *r, struct stray_error *err)
{
	struct stray_fdr_model t = fm->m, v = fm->m;
	int R = (int)floor(sqrt(fm->win.n_px / 3.14159265358979) + 0.5), rc;
	double lf;

	/* eq. 2.18 as the thesis writes it: Gaussian, no detector noise */
	t.noise = STRAY_NOISE_GAUSS;
	t.read_noise_e = 0.0;
	t.dark_current_e_s = 0.0;
	if ((rc = stray_fdr_log_rate(&t, fm->alpha_eff, fm->i_sdt_e, &lf, err)))
		return rc;
	r->thesis = exp(lf);
	if ((rc = stray_fdr_log_rate(&fm->m, fm->alpha_eff, fm->i_sdt_e, &lf,
				     err)))
		return rc;
	r->model = exp(lf);
	/* The sliding window is tested where it fits on the frame. */
	v.n_tot = (double)(fm->cols - 2 * R) * (fm->rows - 2 * R);
	if ((rc = stray_fdr_log_rate_sliding(&v, &fm->win, fm->alpha_eff,
					     fm->i_sdt_e, &lf, err)))
		return rc;
	r->sliding = exp(lf);
	return cluster_rate(fm, &r->clusters, err);
}

int frames_alpha_required(const struct frames_model *fm,
			  const struct stray_sensor *s, double k_px,
			  double rate, struct frames_alpha_req *a,
			  struct stray_error *err)
{
	struct stray_fdr_model m = fm->m, t = fm->m;
	int R = (int)floor(sqrt(fm->win.n_px / 3.14159265358979) + 0.5), rc;

	m.map = NULL;
	m.n_tot = s->pixels_x * s->pixels_y;
	t = m;
	t.noise = STRAY_NOISE_GAUSS;		/* the toolkit today */
	t.read_noise_e = 0.0;
	t.dark_current_e_s = 0.0;
	if ((rc = stray_fdr_alpha_required(&t, rate, &a->thesis_k1, err)) ||
	    (rc = stray_fdr_alpha_required(&m, rate, &a->model, err)))
		return rc;
	m.n_tot = (s->pixels_x - 2 * R) * (s->pixels_y - 2 * R);
	rc = stray_fdr_alpha_required_sliding(&m, &fm->win, fm->i_sdt_e, rate,
					      &a->extended, err);
	a->model /= k_px;
	a->extended /= k_px;
	return rc;
}

void frames_detect_cfg_init(struct frames_detect_cfg *c,
			    const struct frames_model *fm,
			    const struct stray_sensor *s)
{
	(void)s;
	c->bias_dn = STRAY_FRAMES_BIAS_DN;
	c->gain_e_per_dn = STRAY_FRAMES_GAIN_E_PER_DN;
	c->tile_px = 128;
	c->window_radius_px = floor(sqrt(fm->win.n_px / 3.14159265358979) + 0.5);
	c->i_sdt_e = fm->i_sdt_e;
	c->pixel_threshold_e = fm->pixel_threshold_e;
	c->min_px = fm->min_px;
}

size_t frames_count_false(const struct frames_detect_out *o,
			  const struct stray_star *stars, size_t n_stars,
			  double min_e, double match_px, float *fx, float *fy,
			  size_t *n_f, size_t max_f)
{
	size_t i, j, n_false = o->n > o->max ? o->n - o->max : 0;
	size_t n = o->n < o->max ? o->n : o->max;
	double m2 = match_px * match_px;

	for (i = 0; i < n; i++) {
		const struct frames_detection *d = &o->det[i];
		int hit = 0;

		for (j = 0; j < n_stars && !hit; j++) {
			double dx = stars[j].x - d->x, dy = stars[j].y - d->y;

			hit = stars[j].photons_e >= min_e &&
			      dx * dx + dy * dy <= m2;
		}
		if (hit)
			continue;
		n_false++;
		if (fx && n_f && *n_f < max_f) {
			fx[*n_f] = (float)d->x;
			fy[*n_f] = (float)d->y;
			(*n_f)++;
		}
	}
	return n_false;
}
