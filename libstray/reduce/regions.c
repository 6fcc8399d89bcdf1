/*
 * regions.c - a J image as a region map for the non-uniform FDR model:
 * quantile regions of the per-pixel attenuation J_i / Pbar (eq. 3.8,
 * 3.13), each with its pixel fraction and mean level.
 */
#include <math.h>
#include <stdlib.h>

#include "stray/reduce_map.h"

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

int stray_region_map_from_image(const float *j, size_t n, unsigned n_regions,
				double *scratch, struct stray_region_map *map,
				struct stray_error *err)
{
	double mean = 0.0;
	size_t i, lo;
	unsigned r;

	if (n_regions < 1 || n_regions > STRAY_MAP_REGIONS_MAX || n < n_regions)
		return stray_error_set_value(err, STRAY_EINVAL, "regions",
			"must be 1..64 and at most the pixel count",
			(double)n_regions);
	for (i = 0; i < n; i++) {
		scratch[i] = j[i];
		mean += j[i];
	}
	mean /= (double)n;	/* eq. 3.13: Pbar; J_i / Pbar = alpha_px,i / abar_px
				 * by eq. 3.8 and eq. 3.10 */
	if (!(mean > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL, "J",
			"image mean must be > 0 for a map", mean);
	qsort(scratch, n, sizeof(*scratch), cmp_double);
	map->n = n_regions;
	for (r = 0, lo = 0; r < n_regions; r++) {
		size_t hi = n * (r + 1) / n_regions;
		double s = 0.0;

		for (i = lo; i < hi; i++)
			s += scratch[i];
		map->fraction[r] = (double)(hi - lo) / (double)n;
		/* negative noise at the dark end is kept at zero light */
		map->rel_alpha[r] = fmax(s / (double)(hi - lo) / mean, 0.0);
		lo = hi;
	}
	return STRAY_OK;
}
