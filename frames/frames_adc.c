/*
 * frames_adc.c - the lost-star models as each rendered frame sets the
 * detectors' thresholds (frames_adc.h).
 */
#include <math.h>
#include <string.h>

#include "frames/frames_adc.h"

/* Position of p between tile centres along one axis (frames_detect.cpp's
 * axis_weights): the lower tile and the weight of the next. */
static void axis_at(int n, int tile, int nt, double p, int *i0, double *w)
{
	int k = 0;
	double c0, c1;

	if (nt < 2) {
		*i0 = 0;
		*w = 0.0;
		return;
	}
	while (k < nt - 2 && p > (k + 1) * tile +
	       0.5 * (n - (k + 1) * tile < tile ? n - (k + 1) * tile : tile))
		k++;
	c0 = k * tile + 0.5 * (n - k * tile < tile ? n - k * tile : tile);
	c1 = (k + 1) * tile + 0.5 * (n - (k + 1) * tile < tile ?
				     n - (k + 1) * tile : tile);
	*i0 = k;
	*w = (p - c0) / (c1 - c0);
}

double frames_adc_bg_at(const struct frames_adc *a, double x, double y)
{
	int i0, j0, i1, j1;
	double wx, wy, top, bot;
	const float *t = a->tiles;

	axis_at(a->cols, a->tile_px, a->tiles_x, x, &i0, &wx);
	axis_at(a->rows, a->tile_px, a->tiles_y, y, &j0, &wy);
	i1 = i0 + 1 < a->tiles_x ? i0 + 1 : a->tiles_x - 1;
	j1 = j0 + 1 < a->tiles_y ? j0 + 1 : a->tiles_y - 1;
	top = t[j0 * a->tiles_x + i0] +
	      wx * (t[j0 * a->tiles_x + i1] - t[j0 * a->tiles_x + i0]);
	bot = t[j1 * a->tiles_x + i0] +
	      wx * (t[j1 * a->tiles_x + i1] - t[j1 * a->tiles_x + i0]);
	return top + wy * (bot - top);
}

double frames_adc_level_at(const struct frames_adc *a, double x, double y)
{
	int i = (int)floor(x), j = (int)floor(y);
	double w = 1.0;

	if (a->weight) {
		i = i < 0 ? 0 : i >= a->cols ? a->cols - 1 : i;
		j = j < 0 ? 0 : j >= a->rows ? a->rows - 1 : j;
		w = a->weight[(size_t)j * a->cols + i];
	}
	return a->stray_e * w + a->dark_e;
}

double frames_adc_threshold(double t_e, double bg_e, double level_e,
			    double gain_e_per_dn)
{
	double u = (t_e + bg_e) / gain_e_per_dn;

	return t_e + (bg_e - level_e) + gain_e_per_dn * (0.5 - (u - floor(u)));
}

int frames_adc_star_prob(const struct frames_adc *a,
			 const struct stray_detector *d,
			 const struct stray_fdr_model *m, double alpha_eff,
			 double x, double y, double star_e, double *p,
			 struct stray_error *err)
{
	struct stray_detector dd;
	struct stray_fdr_model mm = *m;
	double level = frames_adc_level_at(a, x, y);
	double bg = frames_adc_bg_at(a, x, y), w = 1.0;
	int i = (int)floor(x), j = (int)floor(y), rc;

	if (a->weight) {
		i = i < 0 ? 0 : i >= a->cols ? a->cols - 1 : i;
		j = j < 0 ? 0 : j >= a->rows ? a->rows - 1 : j;
		w = a->weight[(size_t)j * a->cols + i];
	}
	mm.map = NULL;		/* the star's own place: its local level */
	memcpy(&dd, d, sizeof(dd));
	dd.bg_resid_rel = 0;	/* b^ - L at the star is this frame's error */
	if (d->kind == STRAY_DET_WINDOW) {
		dd.i_sdt_e = d->i_sdt_e + d->win.n_px * (bg - level);
	} else if (d->kind == STRAY_DET_THRESHOLD) {
		dd.pixel_t_e = frames_adc_threshold(d->pixel_t_e, bg, level,
						    a->gain_e_per_dn);
		mm.read_noise_e = a->read_noise_e;
	}
	rc = stray_detector_star_prob(&dd, &mm, alpha_eff * w, star_e, p, err);
	return rc;
}

int frames_adc_window_found(const struct frames_detect_out *o, double x,
			    double y, double reach)
{
	size_t n = o->n < o->max ? o->n : o->max, k;

	for (k = 0; k < n; k++) {
		const struct frames_detection *d = &o->det[k];
		double cx = x < d->x0 ? d->x0 : x > d->x1 ? d->x1 : x;
		double cy = y < d->y0 ? d->y0 : y > d->y1 ? d->y1 : y;

		if ((cx - x) * (cx - x) + (cy - y) * (cy - y) <= reach * reach)
			return 1;
	}
	return 0;
}
