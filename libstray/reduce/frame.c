/*
 * frame.c - Bayer read channels and the sanity of one frame (thesis §3.2,
 * fig. 3.5).
 */
#include <math.h>

#include "stray/reduce_frame.h"

void stray_bayer_default(struct stray_bayer_map *m)
{
	unsigned i;

	/* Channel numbers are the index itself: G11 R1 G12 R2 / B1 G21 B2 G22. */
	for (i = 0; i < 8; i++)
		m->ch[i] = (unsigned char)i;
}

int stray_bayer_parse(const char *text, struct stray_bayer_map *m,
		      struct stray_error *err)
{
	unsigned i;

	for (i = 0; i < 8; i++) {
		if (text[i] < '0' || text[i] > '7')
			return stray_error_set(err, STRAY_EPARSE, "channels",
				"expected 8 digits 0..7, one per (row%2, col%4)");
		m->ch[i] = (unsigned char)(text[i] - '0');
	}
	if (text[8] != '\0')
		return stray_error_set(err, STRAY_EPARSE, "channels",
			"expected 8 digits 0..7, one per (row%2, col%4)");
	return STRAY_OK;
}

unsigned stray_bayer_channel(const struct stray_bayer_map *m, long row,
			     long col)
{
	unsigned r = (unsigned)(((row % 2) + 2) % 2);
	unsigned c = (unsigned)(((col % 4) + 4) % 4);

	return m->ch[r * 4 + c];
}

int stray_frame_check(const struct stray_frame *f, struct stray_error *err)
{
	if (f->n_rows == 0 || f->n_cols == 0 || !f->pix || !f->det_row)
		return stray_error_set(err, STRAY_EINVAL, "NAXIS",
				       "frame has no pixels");
	if (!(isfinite(f->t_exp_s) && f->t_exp_s > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "EXPTIME",
			"must be finite and > 0", f->t_exp_s);
	if (!(isfinite(f->nd_trans) && f->nd_trans > 0.0 && f->nd_trans <= 1.0))
		return stray_error_set_value(err, STRAY_EINVAL, "NDTRANS",
			"must be in (0, 1]", f->nd_trans);
	if (!(isfinite(f->monitor) && f->monitor > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "MONITOR",
			"must be finite and > 0", f->monitor);
	if (f->sat_level <= 0 || f->sat_level > 65536)
		return stray_error_set_value(err, STRAY_EINVAL, "SATLEVEL",
			"must be in 1..65536", (double)f->sat_level);
	return STRAY_OK;
}

int stray_frame_sat_at(const struct stray_frame *f)
{
	return f->sat_level < 0 ? 0 : f->sat_level > 65536 ? 65536 :
	       (int)f->sat_level;
}

int stray_frame_clip_check(const struct stray_frame *f,
			   struct stray_error *err)
{
	size_t i, n = f->n_rows * f->n_cols, at_max = 0, below = 0;
	unsigned vmax = 0;
	int k;

	for (i = 0; i < n; i++)
		if (f->pix[i] > vmax)
			vmax = f->pix[i];
	for (k = 8; k <= 16 && (1UL << k) - 1 != vmax; k++)
		;
	if (k > 16 || (long)vmax >= f->sat_level || vmax == 0)
		return STRAY_OK;
	for (i = 0; i < n; i++) {
		at_max += f->pix[i] == vmax;
		below += f->pix[i] == vmax - 1;
	}
	if (at_max < 3 || at_max <= 2 * below)
		return STRAY_OK;
	return stray_error_set_value(err, STRAY_EINVAL, "counts clipped at",
		"pile-up at an ADC full scale (2^k - 1 DN) below the "
		"frame's SATLEVEL, so its counts are not what they say; set "
		"camera.sat_dn to at most it and measure again",
		(stray_real)vmax);
}
