/*
 * flightcheck_bg.c - the background of a flight frame (mission/flightcheck.h,
 * step 2 of docs/flightcheck.md): tile medians and a plane.
 */
#include <math.h>
#include <stdlib.h>

#include "mission/flightcheck.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* Grouped median of 12-bit samples (interpolated inside the median's
 * DN step, so a 2 e-/DN ADC does not quantise the background) and half
 * the interquartile range, by counting (hist: 4096 zeroed bins, left
 * zeroed). */
static double grouped_median(const uint16_t *s, size_t n, uint32_t *hist,
			     double *half_iqr)
{
	size_t i, cum = 0, q1 = 0, q3 = 0;
	unsigned lo = 4095, hi = 0, v, med = 0;
	size_t below = 0, at = 1;
	int got_med = 0, got_q1 = 0;

	for (i = 0; i < n; i++) {
		v = s[i] > 4095 ? 4095 : s[i];
		hist[v]++;
		if (v < lo)
			lo = v;
		if (v > hi)
			hi = v;
	}
	for (v = lo; v <= hi; v++) {
		size_t h = hist[v];

		if (!got_q1 && cum + h > n / 4) {
			q1 = v;
			got_q1 = 1;
		}
		if (!got_med && cum + h > n / 2) {
			med = v;
			below = cum;
			at = h;
			got_med = 1;
		}
		if (cum + h > (3 * n) / 4) {
			q3 = v;
			break;
		}
		cum += h;
	}
	for (v = lo; v <= hi; v++)
		hist[v] = 0;
	*half_iqr = 0.5 * ((double)q3 - (double)q1);
	return med - 0.5 + (0.5 * n - below) / (double)at;
}

/* Background: a grouped median per tile (stars, hot pixels and cosmic
 * rays are a minority of a tile), a plane fitted to the tiles with two
 * 3-sigma rejections. */
void fc_background(const struct fc_cfg *c, struct fc_work *w,
		   const uint16_t *dn, double plane[3], struct fc_frame *o)
{
	int tx = (c->cols + FC_TILE_PX - 1) / FC_TILE_PX;
	int ty = (c->rows + FC_TILE_PX - 1) / FC_TILE_PX, i, j, it;
	double *tc = malloc((size_t)tx * ty * 3 * sizeof(double));
	double mads = 0.0, rms = 1e30;
	int n_mad = 0, nt = tx * ty;
	char *use = malloc((size_t)nt);

	for (j = 0; j < ty; j++)
		for (i = 0; i < tx; i++) {
			int x0 = i * FC_TILE_PX, y0 = j * FC_TILE_PX, x, y;
			int x1 = x0 + FC_TILE_PX > c->cols ? c->cols : x0 + FC_TILE_PX;
			int y1 = y0 + FC_TILE_PX > c->rows ? c->rows : y0 + FC_TILE_PX;
			size_t n = 0;
			double mad;
			int k = j * tx + i;

			for (y = y0; y < y1; y++)
				for (x = x0 + (y & 1); x < x1; x += 2)
					w->sample[n++] = dn[(size_t)y * c->cols + x];
			w->tile_med[k] = (float)grouped_median(w->sample, n, w->hist,
								&mad);
			tc[3 * k] = 0.5 * (x0 + x1) - 0.5 * c->cols;
			tc[3 * k + 1] = 0.5 * (y0 + y1) - 0.5 * c->rows;
			tc[3 * k + 2] = w->tile_med[k];
			mads += mad / 0.6745;
			n_mad++;
			use[k] = 1;
		}
	o->noise_dn = mads / n_mad;
	plane[0] = plane[1] = plane[2] = 0.0;
	for (it = 0; it < 3; it++) {
		/* least squares a + b x + c y; the tile centres are centred,
		 * so the normal matrix is nearly diagonal: solve it 3x3 */
		double s[3][4] = { { 0 } }, r2 = 0.0;
		int n = 0, k, p, q;

		for (k = 0; k < nt; k++) {
			double v[3] = { 1.0, tc[3 * k], tc[3 * k + 1] };

			if (!use[k])
				continue;
			for (p = 0; p < 3; p++) {
				for (q = 0; q < 3; q++)
					s[p][q] += v[p] * v[q];
				s[p][3] += v[p] * tc[3 * k + 2];
			}
			n++;
		}
		/* Gauss-Jordan on the 3x4 system */
		for (p = 0; p < 3; p++) {
			double d = s[p][p];

			if (fabs(d) < 1e-12) {
				s[p][3] = 0.0;
				continue;
			}
			for (q = 0; q < 4; q++)
				s[p][q] /= d;
			for (k = 0; k < 3; k++) {
				double f = s[k][p];

				if (k == p)
					continue;
				for (q = 0; q < 4; q++)
					s[k][q] -= f * s[p][q];
			}
		}
		plane[0] = s[0][3];
		plane[1] = s[1][3];
		plane[2] = s[2][3];
		for (k = 0; k < nt; k++) {
			double e = tc[3 * k + 2] - plane[0] -
				   plane[1] * tc[3 * k] - plane[2] * tc[3 * k + 1];

			if (use[k])
				r2 += e * e;
		}
		rms = n > 3 ? sqrt(r2 / (n - 3)) : o->noise_dn;
		o->n_tiles_used = n;
		if (it == 2)
			break;
		for (k = 0; k < nt; k++) {
			double e = tc[3 * k + 2] - plane[0] -
				   plane[1] * tc[3 * k] - plane[2] * tc[3 * k + 1];

			use[k] = fabs(e) <= 3.0 * rms + 1e-9;
		}
	}
	o->bg_dn = plane[0];
	/* error of the mean: the tiles' scatter about the plane, or the
	 * pixel noise of the samples when that is larger */
	o->bg_sigma_dn = fmax(rms, o->noise_dn * 1.2533 /
			      sqrt(FC_TILE_PX * FC_TILE_PX / 2.0)) /
			 sqrt((double)(o->n_tiles_used > 0 ? o->n_tiles_used : 1));
	/* plus a systematic floor: the median's bias from faint stars
	 * nobody resolves (up to ~0.05 DN in the hidden-effect frames) */
	o->bg_sigma_dn = hypot(o->bg_sigma_dn, FC_BG_SYS_DN);
	o->grad_dn_per_px = hypot(plane[1], plane[2]);
	o->grad_dir_deg = atan2(plane[2], plane[1]) / DEG;
	free(tc);
	free(use);
}

