/*
 * frames_io.h - a focal-plane map's weights (read by focal_map_load,
 * focal_map_io.h) as the regions of the FDR model.  Rendered frames are
 * written through the sweep store (stray/sweep_store.h).
 */
#ifndef STRAY_FRAMES_FRAMES_IO_H
#define STRAY_FRAMES_FRAMES_IO_H

#include <stddef.h>

#include "stray/fdr.h"

/* The weights as a region map of up to 64 levels (for the model). */
void frames_map_regions(const float *weight, size_t n,
			struct stray_region_map *map);

#endif /* STRAY_FRAMES_FRAMES_IO_H */
