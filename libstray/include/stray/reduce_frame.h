/*
 * reduce_frame.h - one lab frame as the reduction sees it (thesis §3.2):
 * detector counts of the stored rows, where they sit on the detector, and
 * the Bayer read channel of every pixel.  Caller-owned memory; no I/O.
 */
#ifndef STRAY_REDUCE_FRAME_H
#define STRAY_REDUCE_FRAME_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"

/* The MT9P031 reads through 8 channels (G11 G12 G21 G22 R1 R2 B1 B2). */
#define STRAY_BAYER_CHANNELS 8

/*
 * Read channel of a pixel by (detector row mod 2, detector column mod 4):
 * ch[(row % 2) * 4 + col % 4].  The default is the thesis's fig. 3.5
 * layout: row 0 = G11 R1 G12 R2, row 1 = B1 G21 B2 G22 (channels numbered
 * 0..7 in that order).
 */
struct stray_bayer_map {
	unsigned char ch[8];
};

void stray_bayer_default(struct stray_bayer_map *m);

/*
 * Parse a map written as 8 digits 0..7 ("01234567" is the identity
 * layout: index (row%2)*4 + col%4).  STRAY_EPARSE names "channels".
 */
int stray_bayer_parse(const char *text, struct stray_bayer_map *m,
		      struct stray_error *err);

/* Channel of detector pixel (row, col); negative indices wrap. */
unsigned stray_bayer_channel(const struct stray_bayer_map *m, long row,
			     long col);

/* One frame: n_rows stored rows of n_cols counts, row-major. */
struct stray_frame {
	size_t n_rows, n_cols;
	const uint16_t *pix;
	const long *det_row;	/* detector row of each stored row */
	long col0;		/* detector column of stored column 0 */
	double t_exp_s;		/* EXPTIME */
	double nd_trans;	/* NDTRANS, 0 < nd <= 1 */
	double monitor;		/* MONITOR source reading, 1 when absent */
	long sat_level;		/* SATLEVEL: counts >= this are saturated */
};

/* Finite positive exposure, 0 < nd <= 1, monitor > 0, pixels present. */
int stray_frame_check(const struct stray_frame *f, struct stray_error *err);

/* SATLEVEL as an int a 16-bit sample compares with, clamped to 0..65536:
 * pix >= it is exactly (long)pix >= sat_level, without widening. */
int stray_frame_sat_at(const struct stray_frame *f);

/*
 * A frame clipped below its SATLEVEL: its largest count is 2^k - 1
 * (k = 8..16, an ADC's full scale), under SATLEVEL, and at least three
 * pixels pile up there (more than twice as many as one count below).
 * Such a frame says its counts are good to SATLEVEL when the ADC stopped
 * earlier, so every clipped sample would enter the curve as a true one
 * (camera.sat_dn above the ADC: alpha 1.0 at every angle).  Returns
 * STRAY_EINVAL with SATLEVEL and the clip level in the message.
 */
int stray_frame_clip_check(const struct stray_frame *f,
			   struct stray_error *err);

#endif /* STRAY_REDUCE_FRAME_H */
