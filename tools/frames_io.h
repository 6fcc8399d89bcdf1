/*
 * frames_io.h - the files of `stray frames`: a rendered frame as a lab
 * frame (FITS, keywords of docs/formats.md, cfitsio), and a focal-plane
 * map's weights (read by focal_map_load, focal_map_io.h) as the regions
 * of the FDR model.
 */
#ifndef STRAY_TOOLS_FRAMES_IO_H
#define STRAY_TOOLS_FRAMES_IO_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"
#include "stray/fdr.h"

struct frames_fits_meta {
	double theta_deg, t_exp_s, alpha, k_px, stray_e;
	const char *normalisation;
	int seqnum, col0, row0, sat_dn;
	size_t n_stars;
};

/* Write one frame (rows x cols DN) to path; STRAY_EIO names the file. */
int frames_fits_write(const char *path, const uint16_t *dn, int cols,
		      int rows, const struct frames_fits_meta *m,
		      struct stray_error *err);

/* The weights as a region map of up to 64 levels (for the model). */
void frames_map_regions(const float *weight, size_t n,
			struct stray_region_map *map);

#endif /* STRAY_TOOLS_FRAMES_IO_H */
