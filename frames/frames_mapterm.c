/*
 * frames_mapterm.c - the background-error term of a focal map
 * (frames_mapterm.h).
 */
#include <math.h>
#include <stdlib.h>

#include "frames/frames_adc.h"
#include "frames/frames_mapterm.h"
#include "stray/detector.h"

double frames_map_resid_rel(const float *w, int cols, int rows, int tile_px)
{
	struct frames_adc a;
	float *t;
	double s2 = 0.0;
	int tx, ty, i, j, x, y;

	if (!w)
		return 0.0;
	frames_detect_tiles(cols, rows, tile_px, &tx, &ty);
	t = calloc((size_t)tx * ty, sizeof(*t));
	if (!t)
		return NAN;
	for (j = 0; j < ty; j++)
		for (i = 0; i < tx; i++) {
			double sum = 0.0;
			long n = 0;

			for (y = j * tile_px; y < rows && y < (j + 1) * tile_px; y++)
				for (x = i * tile_px; x < cols &&
				     x < (i + 1) * tile_px; x++, n++)
					sum += w[(size_t)y * cols + x];
			t[j * tx + i] = (float)(sum / n);
		}
	a.tiles = t;
	a.tiles_x = tx;
	a.tiles_y = ty;
	a.tile_px = tile_px;
	a.cols = cols;
	a.rows = rows;
	/* relative to the local weight: the structure multiplies the light
	 * (detector.c's eq. R scales it by each region's level) */
	for (y = 0; y < rows; y++)
		for (x = 0; x < cols; x++) {
			double v = w[(size_t)y * cols + x], d;

			if (!(v > 0.0))
				continue;
			d = (v - frames_adc_bg_at(&a, x + 0.5, y + 0.5)) / v;
			s2 += d * d;
		}
	free(t);
	return sqrt(s2 / ((double)cols * rows));
}

int frames_mapterm_rates(const struct frames_model *fm, double resid_rel,
			 double *window, double *threshold,
			 struct stray_error *err)
{
	static struct stray_detector d;	/* the animal table is large */
	struct stray_fdr_model m = fm->m;
	int R = (int)floor(sqrt(fm->win.n_px / 3.14159265358979) + 0.5), k, rc;
	double lr;

	for (k = 0; k < 2; k++) {
		stray_detector_init(&d, k ? STRAY_DET_THRESHOLD :
				    STRAY_DET_WINDOW, m.n_pps);
		if ((rc = stray_detector_setup(&d, &m, err)) != STRAY_OK)
			return rc;
		d.i_sdt_e = fm->i_sdt_e;	/* the OpenCV detectors' */
		d.pixel_t_e = fm->pixel_threshold_e;
		d.bg_resid_rel = resid_rel;
		/* the window is tested where it fits (frames_run.c) */
		m.n_tot = k ? (double)fm->cols * fm->rows :
			      (double)(fm->cols - 2 * R) * (fm->rows - 2 * R);
		if ((rc = stray_detector_log_false_rate(&d, &m, fm->alpha_eff,
							&lr, err)) != STRAY_OK)
			return rc;
		*(k ? threshold : window) = exp(lr);
	}
	return STRAY_OK;
}
