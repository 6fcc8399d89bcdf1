/*
 * flightcheck.c - the per-frame step and the summary of `stray
 * flightcheck` (mission/flightcheck.h; thesis §4.3, eq. 2.2, 2.3, 2.12).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mission/flightcheck.h"
#include "fdrfw/ephem.h"
#include "stray/aem.h"
#include "stray/photometry_io.h"
#include "stray/sensor.h"
#include "stray/sensor_geom.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define CAT_MAX 65536
#define PRED_MAX 4096

int fc_work_alloc(struct fc_work *w, const struct fc_cfg *c)
{
	size_t nt = (size_t)((c->cols + FC_TILE_PX - 1) / FC_TILE_PX) *
		    (size_t)((c->rows + FC_TILE_PX - 1) / FC_TILE_PX);

	memset(w, 0, sizeof(*w));
	w->cat_max = CAT_MAX;
	w->pred_max = PRED_MAX;
	w->cat = malloc(CAT_MAX * sizeof(*w->cat));
	w->pred = malloc(PRED_MAX * sizeof(*w->pred));
	w->tile_med = malloc(nt * sizeof(*w->tile_med));
	w->sample = malloc(FC_TILE_PX * FC_TILE_PX * sizeof(*w->sample));
	w->hist = calloc(4096, sizeof(*w->hist));
	w->mx = malloc(2 * PRED_MAX * sizeof(*w->mx));
	w->my = w->mx ? w->mx + PRED_MAX : NULL;
	if (!w->cat || !w->pred || !w->tile_med || !w->sample || !w->mx ||
	    !w->hist) {
		fc_work_free(w);
		return -1;
	}
	return 0;
}

void fc_work_free(struct fc_work *w)
{
	free(w->cat);
	free(w->pred);
	free(w->tile_med);
	free(w->sample);
	free(w->mx);
	free(w->hist);
	memset(w, 0, sizeof(*w));
}

double fc_sun_angle_deg(const double q_ib[4], double t_tt)
{
	double m[3][3], d;
	float s[3];

	stray_q_dcm(q_ib, m);
	fdrfw_sun_dir((int32_t)lround(t_tt), s);
	/* the head's +z in inertial coordinates: row 2 of M (v_b = M v_i) */
	d = m[2][0] * s[0] + m[2][1] * s[1] + m[2][2] * s[2];
	d /= sqrt((double)s[0] * s[0] + (double)s[1] * s[1] +
		  (double)s[2] * s[2]);
	return acos(fmax(-1.0, fmin(1.0, d))) / DEG;
}

static double bg_at(const double plane[3], const struct fc_cfg *c,
		    double x, double y)
{
	return plane[0] + plane[1] * (x - 0.5 * c->cols) +
	       plane[2] * (y - 0.5 * c->rows);
}

/* The brightest pixel within half-width s of (x, y), then the
 * intensity centroid of the 5x5 around it; 0 when under 5 sigma. */
static int locate(const struct fc_cfg *c, const uint16_t *dn,
		  const double plane[3], double noise, double x, double y,
		  double s, double *cx, double *cy)
{
	int x0 = (int)floor(x - s), x1 = (int)floor(x + s);
	int y0 = (int)floor(y - s), y1 = (int)floor(y + s), i, j, bi = -1, bj = -1;
	double best = 5.0 * noise, sw = 0.0, sx = 0.0, sy = 0.0;

	if (x0 < 2) x0 = 2;
	if (y0 < 2) y0 = 2;
	if (x1 > c->cols - 3) x1 = c->cols - 3;
	if (y1 > c->rows - 3) y1 = c->rows - 3;
	for (j = y0; j <= y1; j++)
		for (i = x0; i <= x1; i++) {
			double v = dn[(size_t)j * c->cols + i] -
				   bg_at(plane, c, i + 0.5, j + 0.5);

			if (v > best) {
				best = v;
				bi = i;
				bj = j;
			}
		}
	if (bi < 0)
		return 0;
	for (j = bj - 2; j <= bj + 2; j++)
		for (i = bi - 2; i <= bi + 2; i++) {
			double v = dn[(size_t)j * c->cols + i] -
				   bg_at(plane, c, i + 0.5, j + 0.5);

			if (v <= 0.0)
				continue;
			sw += v;
			sx += v * (i + 0.5);
			sy += v * (j + 0.5);
		}
	*cx = sx / sw;
	*cy = sy / sw;
	return 1;
}

/* The aperture sum above the background plane; 0 when clipped by an
 * edge or saturated. */
static int aperture(const struct fc_cfg *c, const uint16_t *dn,
		    const double plane[3], double noise, double x, double y,
		    double *sum, int *npix)
{
	double r = FC_APERTURE_PX, s = 0.0;
	int i, j, n = 0;

	if (x - r < 1 || y - r < 1 || x + r >= c->cols - 1 ||
	    y + r >= c->rows - 1)
		return 0;
	for (j = (int)floor(y - r); j <= (int)floor(y + r); j++)
		for (i = (int)floor(x - r); i <= (int)floor(x + r); i++) {
			double dx = i + 0.5 - x, dy = j + 0.5 - y;
			uint16_t v = dn[(size_t)j * c->cols + i];

			if (dx * dx + dy * dy > r * r)
				continue;
			double b = bg_at(plane, c, i + 0.5, j + 0.5), nb;

			if (v >= c->sat_dn - 1)
				return 0;
			/* a hot pixel: far above all four neighbours (the
			 * PSF's centre is only 1.25x its neighbours) */
			nb = fmax(fmax(dn[(size_t)j * c->cols + i - 1],
				       dn[(size_t)j * c->cols + i + 1]),
				  fmax(dn[(size_t)(j - 1) * c->cols + i],
				       dn[(size_t)(j + 1) * c->cols + i])) - b;
			if (v - b > 5.0 * noise && v - b > 2.5 * fmax(nb, noise))
				v = (uint16_t)lround(b + fmax(nb, 0.0));
			s += v - b;
			n++;
		}
	*sum = s;
	*npix = n;
	return 1;
}

/* Whether a catalogue neighbour puts over 1 % of star k's light into its
 * window (double stars are common on the real sky: +0.5 % in DN/e-). */
static int blended(const struct stray_star *p, size_t n, size_t k)
{
	double r = 2.0 * FC_APERTURE_PX;
	size_t j;

	for (j = 0; j < n; j++)
		if (j != k && fabs(p[j].x - p[k].x) < r &&
		    fabs(p[j].y - p[k].y) < r &&
		    p[j].photons_e > 0.01 * p[k].photons_e)
			return 1;
	return 0;
}

/* Least squares of a small rotation phi about the axis point and a shift
 * (dx, dy): measured - predicted = (dx - phi y', dy + phi x'). */
static void refine(const struct fc_cfg *c, const struct stray_star *p,
		   const int *idx, const double *mx, const double *my, int n,
		   double out[3])
{
	double a[3][4] = { { 0 } };
	int k, r, q;

	out[0] = out[1] = out[2] = 0.0;
	if (n == 0)
		return;
	for (k = 0; k < n; k++) {
		double xp = p[idx[k]].x - c->cx, yp = p[idx[k]].y - c->cy;
		double rows[2][3] = { { 1.0, 0.0, -yp }, { 0.0, 1.0, xp } };
		double d[2] = { mx[k] - p[idx[k]].x, my[k] - p[idx[k]].y };
		int e;

		for (e = 0; e < 2; e++)
			for (r = 0; r < 3; r++) {
				for (q = 0; q < 3; q++)
					a[r][q] += rows[e][r] * rows[e][q];
				a[r][3] += rows[e][r] * d[e];
			}
	}
	if (n < 3) {	/* a shift only */
		out[0] = a[0][3] / a[0][0];
		out[1] = a[1][3] / a[1][1];
		return;
	}
	for (r = 0; r < 3; r++) {
		double d = a[r][r];

		for (q = 0; q < 4; q++)
			a[r][q] /= d;
		for (k = 0; k < 3; k++) {
			double f = a[k][r];

			if (k == r)
				continue;
			for (q = 0; q < 4; q++)
				a[k][q] -= f * a[r][q];
		}
	}
	out[0] = a[0][3];
	out[1] = a[1][3];
	out[2] = a[2][3];
}

void fc_frame_analyse(const struct fc_cfg *c, struct fc_work *w,
		      const uint16_t *dn, const double q_ib[4], double t_tt,
		      struct fc_frame *o)
{
	struct stray_camera cam;
	double plane[3], dir[3], radius, sol[3] = { 0 }, r2 = 0.0;
	size_t n_cat, n_pred, i;
	int *idx, n_match = 0, k;

	memset(o, 0, sizeof(*o));
	o->t_tt = t_tt;
	o->theta_deg = fc_sun_angle_deg(q_ib, t_tt);
	fc_background(c, w, dn, plane, o);

	/* the plate solution from the attitude: the catalogue in the cone
	 * around the boresight, projected by the ideal camera */
	stray_q_dcm(q_ib, cam.m_ih);
	cam.f_px = c->f_px;
	cam.cx = c->cx;
	cam.cy = c->cy;
	dir[0] = cam.m_ih[2][0];
	dir[1] = cam.m_ih[2][1];
	dir[2] = cam.m_ih[2][2];
	radius = atan(0.5 * hypot(c->cols, c->rows) / c->f_px +
		      hypot(c->cx - 0.5 * c->cols, c->cy - 0.5 * c->rows) /
		      c->f_px) / DEG + 0.2;
	if (c->starcat) {	/* the real sky at the frame's epoch */
		stray_starcat_cone(c->starcat, stray_jyear_of_tt(t_tt), dir,
				   radius, FC_MAG_CAL, w->cat, w->cat_max,
				   &n_cat);
		if (c->colour)
			stray_colour_apply(c->colour, w->cat, n_cat);
	} else {
		stray_catalogue_cone(c->cat_seed, dir, radius, FC_MAG_CAL,
				     w->cat, w->cat_max, &n_cat);
	}
	n_pred = stray_camera_stars(&cam, w->cat, n_cat, c->cols, c->rows,
				    0.0, c->f0_e, w->pred, w->pred_max);
	o->n_pred = (int)n_pred;

	/* match: each predicted star found near its place */
	idx = calloc(n_pred + 1, sizeof(*idx));
	if (!idx)	/* no stars: the verdict refuses the frame set */
		return;
	for (i = 0; i < n_pred; i++) {
		double mx, my;

		if (locate(c, dn, plane, o->noise_dn, w->pred[i].x,
			   w->pred[i].y, c->search_px, &mx, &my)) {
			w->mx[n_match] = mx;
			w->my[n_match] = my;
			idx[n_match++] = (int)i;
		}
	}
	/* refine on the matches, reject the worst (> 3 px) once, again */
	refine(c, w->pred, idx, w->mx, w->my, n_match, sol);
	for (k = 0, i = 0; k < n_match; k++) {
		struct stray_star *p = &w->pred[idx[k]];
		double xp = p->x - c->cx, yp = p->y - c->cy;
		double ex = w->mx[k] - (p->x + sol[0] - sol[2] * yp);
		double ey = w->my[k] - (p->y + sol[1] + sol[2] * xp);

		if (ex * ex + ey * ey <= 9.0) {
			w->mx[i] = w->mx[k];
			w->my[i] = w->my[k];
			idx[i++] = idx[k];
		}
	}
	n_match = (int)i;
	refine(c, w->pred, idx, w->mx, w->my, n_match, sol);
	/* the stars too bright to be missed, and how many were found
	 * (the matches kept by the plate solution, in order) */
	for (k = 0, i = 0; i < n_pred; i++) {
		if (w->pred[i].photons_e / c->gain_e_per_dn <
		    FC_SURE_SNR * o->noise_dn)
			continue;
		o->n_sure++;
		while (k < n_match && idx[k] < (int)i)
			k++;
		o->n_sure_found += k < n_match && idx[k] == (int)i;
	}
	o->n_match = n_match;
	o->dx_px = sol[0];
	o->dy_px = sol[1];
	o->rot_deg = sol[2] / DEG;
	for (k = 0; k < n_match; k++) {
		struct stray_star *p = &w->pred[idx[k]];
		double xp = p->x - c->cx, yp = p->y - c->cy;
		double ex = w->mx[k] - (p->x + sol[0] - sol[2] * yp);
		double ey = w->my[k] - (p->y + sol[1] + sol[2] * xp);

		r2 += ex * ex + ey * ey;
	}
	o->resid_px = n_match > 0 ? sqrt(r2 / n_match) : 0.0;

	/* photometry at the refined positions (not the centroids: no
	 * noise-chasing bias), DN per photo-e- of eq. 2.2 and 2.12 */
	for (i = 0; i < n_pred && n_match > 0; i++) {
		struct stray_star *p = &w->pred[i];
		double xp = p->x - c->cx, yp = p->y - c->cy, sum, var, r;
		double x = p->x + sol[0] - sol[2] * yp;
		double y = p->y + sol[1] + sol[2] * xp;
		int npix;

		if (blended(w->pred, n_pred, i) ||
		    !aperture(c, dn, plane, o->noise_dn, x, y, &sum, &npix))
			continue;
		var = fmax(sum, 0.0) / c->gain_e_per_dn +
		      npix * o->noise_dn * o->noise_dn;
		if (sum < 5.0 * sqrt(var))	/* calibrators: SNR >= 5 */
			continue;
		r = sum / p->photons_e;
		var /= p->photons_e * p->photons_e;
		o->cal_sw += 1.0 / var;
		o->cal_swr += r / var;
		o->cal_swr2 += r * r / var;
		o->n_cal++;
	}
	free(idx);
}

void fc_summarise(const struct fc_cfg *c, const struct fc_frame *f,
		  size_t n, double k_px_model, struct fc_point *pts,
		  struct fc_summary *s)
{
	double sw = 0, swr = 0, swr2 = 0, a = 0, b = 0, chi2 = 0, rel_c;
	size_t i, m = 0;

	memset(s, 0, sizeof(*s));
	s->n_frames = (int)n;
	for (i = 0; i < n; i++) {
		s->n_pred += f[i].n_pred;
		s->n_match += f[i].n_match;
		s->n_sure += f[i].n_sure;
		s->n_sure_found += f[i].n_sure_found;
		s->resid_px += f[i].resid_px * f[i].resid_px * f[i].n_match;
	}
	s->match_frac = s->n_sure > 0 ? (double)s->n_sure_found / s->n_sure
				       : 0.0;
	s->resid_px = s->n_match > 0 ? sqrt(s->resid_px / s->n_match) : 0.0;
	for (i = 0; i < n; i++) {
		sw += f[i].cal_sw;
		swr += f[i].cal_swr;
		swr2 += f[i].cal_swr2;
		s->n_cal += f[i].n_cal;
	}
	if (sw <= 0.0)
		return;
	s->dn_per_e = swr / sw;
	s->cal_chi2_dof = s->n_cal > 1 ?
		(swr2 - swr * swr / sw) / (s->n_cal - 1) : 1.0;
	s->dn_per_e_sigma = sqrt(fmax(1.0, s->cal_chi2_dof) / sw);
	for (i = 0; i < n; i++) {
		/* stray DN -> photo-e- per px -> alpha_px (eq. 2.3) */
		struct fc_cfg at;
		double st;

		fc_cfg_exposure(c, f[i].t_exp_s, &at);	/* its own EXPTIME */
		if (f[i].gain_e_per_dn > 0.0)		/* its own GAIN, BIAS */
			at.gain_e_per_dn = f[i].gain_e_per_dn;
		if (f[i].bias_dn > 0.0)
			at.bias_dn = f[i].bias_dn;
		st = f[i].bg_dn - at.bias_dn - at.dark_e / at.gain_e_per_dn;
		pts[i].theta_deg = f[i].theta_deg;
		pts[i].alpha_px = st / (s->dn_per_e * at.sun_e);
		pts[i].sigma = f[i].bg_sigma_dn / (s->dn_per_e * at.sun_e);
	}
	/* best scale: weighted least squares of alpha_px = scale x model,
	 * over the frames with no Moon or Earth near (screened) */
	for (i = 0; i < n; i++) {
		double w = 1.0 / (pts[i].sigma * pts[i].sigma);

		s->n_screened += f[i].screened;
		if (!(pts[i].model > 0.0) || !(pts[i].sigma > 0.0) ||
		    f[i].screened)
			continue;
		a += w * pts[i].alpha_px * pts[i].model;
		b += w * pts[i].model * pts[i].model;
		m++;
	}
	if (b <= 0.0)
		return;
	s->scale = a / b;
	for (i = 0; i < n; i++) {
		double e;

		if (!(pts[i].model > 0.0) || !(pts[i].sigma > 0.0) ||
		    f[i].screened)
			continue;
		e = (pts[i].alpha_px - s->scale * pts[i].model) / pts[i].sigma;
		chi2 += e * e;
	}
	s->chi2_dof = m > 1 ? chi2 / (double)(m - 1) : 0.0;
	s->scale_sigma_stat = sqrt(fmax(1.0, s->chi2_dof) / b);
	rel_c = s->dn_per_e_sigma / s->dn_per_e;
	s->scale_sigma = hypot(s->scale_sigma_stat, s->scale * rel_c);
	s->k_px_model = k_px_model;
	s->scale_over_kpx = s->scale / k_px_model;
	s->scale_over_kpx_sigma = s->scale_sigma / k_px_model;
}

void fc_cfg_init(struct fc_cfg *c, const struct stray_sensor *s,
		 const struct stray_fluxes *fl, int cols, int rows, int col0,
		 int row0)
{
	double a_cs = PI * 0.25 * s->aperture_diameter_mm *
		      s->aperture_diameter_mm * 1e-6;
	double a_px = s->pixel_pitch_um * s->pixel_pitch_um * 1e-12;

	memset(c, 0, sizeof(*c));
	c->cols = cols;
	c->rows = rows;
	c->f_px = stray_sensor_focal_length_mm(s) / (s->pixel_pitch_um * 1e-3);
	c->cx = 0.5 * s->pixels_x - col0;
	c->cy = 0.5 * s->pixels_y - row0;
	c->t_exp_s = s->t_exp_s;
	c->gain_e_per_dn = STRAY_FRAMES_GAIN_E_PER_DN;
	c->bias_dn = STRAY_FRAMES_BIAS_DN;
	c->sat_dn = STRAY_FRAMES_SAT_DN;
	c->dark_e = s->dark_current_e_s * s->t_exp_s;
	c->f0_e = fl->zero_mag * s->t_exp_s * a_cs;	/* eq. 2.2, 2.12 */
	c->sun_e = fl->sun * s->t_exp_s * a_px;		/* eq. 2.3 per alpha_px */
	c->cat_seed = STRAY_CATALOGUE_SEED;
	c->search_px = 10.0;
}

void fc_cfg_exposure(const struct fc_cfg *c, double t_exp_s,
		     struct fc_cfg *out)
{
	double r = t_exp_s > 0.0 && c->t_exp_s > 0.0 ? t_exp_s / c->t_exp_s
						      : 1.0;

	*out = *c;
	if (r == 1.0)
		return;
	out->t_exp_s = t_exp_s;
	out->dark_e = c->dark_e * r;
	out->f0_e = c->f0_e * r;
	out->sun_e = c->sun_e * r;
}
