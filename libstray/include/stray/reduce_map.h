/*
 * reduce_map.h - a measured J image as the non-uniform stray-light map of
 * the FDR model (stray/fdr.h struct stray_region_map, beyond the thesis's
 * uniform-light assumption of §2.3): pixels grouped into regions of equal
 * size by their level, each region's fraction of the pixels and its mean
 * relative to the image mean.
 */
#ifndef STRAY_REDUCE_MAP_H
#define STRAY_REDUCE_MAP_H

#include <stddef.h>

#include "stray/error.h"
#include "stray/fdr.h"

/*
 * Split the n pixels of j into n_regions quantile regions (1 ..
 * STRAY_MAP_REGIONS_MAX, at most n).  scratch holds n doubles.
 * STRAY_EINVAL when the image mean is not positive.
 */
int stray_region_map_from_image(const float *j, size_t n, unsigned n_regions,
				double *scratch, struct stray_region_map *map,
				struct stray_error *err);

#endif /* STRAY_REDUCE_MAP_H */
