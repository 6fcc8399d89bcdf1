/*
 * frames_detect.h - star detection on rendered (or lab) frames with
 * OpenCV (frames_detect.cpp; OpenCV 4 has no C API).  Two detectors:
 *
 *  - thesis: the window sum of n_pps pixels (a disk of radius r px) of the
 *    background-subtracted frame, tested at every pixel against I_sdt
 *    (eq. 2.11, 2.16); one star per 8-connected above-threshold region.
 *  - threshold: the detector of open star trackers (tetra3, OpenStar-
 *    Tracker): pixels above the local background by more than k sigma_0,
 *    8-connected components of at least min_px pixels, their centroids.
 *
 * Both subtract the same local background: a clipped mean (5 sigma about
 * the median) on square tiles, bilinear between tile centres.
 */
#ifndef STRAY_FRAMES_FRAMES_DETECT_H
#define STRAY_FRAMES_FRAMES_DETECT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum frames_detector { FRAMES_DET_THESIS = 1, FRAMES_DET_THRESHOLD = 2 };

struct frames_detect_cfg {
	double bias_dn, gain_e_per_dn;	/* the camera's calibration */
	int tile_px;			/* background tile side (128) */
	double window_radius_px;	/* thesis: disk radius (6: 113 px) */
	double i_sdt_e;			/* thesis: threshold, eq. 2.16 */
	double pixel_threshold_e;	/* threshold: k sigma_0, e- */
	int min_px;			/* threshold: smallest component */
};

struct frames_detection {
	double x, y;		/* centroid, px (pixel centres at i + 0.5) */
	double n_px;		/* pixels of the region */
	/* the region's bounding box, pixel centres (i + 0.5), inclusive:
	 * the window detector's lost-star rule (frames_lost.h) */
	double x0, y0, x1, y1;
};

struct frames_detect_out {
	struct frames_detection *det;	/* caller's array */
	size_t max, n;			/* n may exceed max: the rest dropped */
};

/*
 * Run the detectors in `which` (a mask of enum frames_detector) on a
 * rows x cols DN frame.  out[0] gets the thesis detections, out[1] the
 * threshold ones.  bg_tiles (tiles_x * tiles_y floats, or NULL) gets the
 * background per tile in e-.  Returns 0, or -1 with a reason in msg.
 */
int frames_detect(const uint16_t *dn, int cols, int rows,
		  const struct frames_detect_cfg *c, int which,
		  struct frames_detect_out out[2], float *bg_tiles,
		  char *msg, size_t msg_size);

/* Tiles of the background grid of a cols x rows frame. */
void frames_detect_tiles(int cols, int rows, int tile_px, int *tiles_x,
			 int *tiles_y);

#ifdef __cplusplus
}
#endif

#endif /* STRAY_FRAMES_FRAMES_DETECT_H */
