/*
 * frames_io.c - a focal map's weights as regions (frames_io.h).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "frames/frames_io.h"

void frames_map_regions(const float *weight, size_t n,
			struct stray_region_map *map)
{
	enum { NB = STRAY_MAP_REGIONS_MAX };
	double lo = INFINITY, hi = -INFINITY, cnt[NB], sum[NB];
	size_t i;
	int b, k = 0;

	memset(cnt, 0, sizeof(cnt));
	memset(sum, 0, sizeof(sum));
	for (i = 0; i < n; i++) {
		lo = fmin(lo, weight[i]);
		hi = fmax(hi, weight[i]);
	}
	for (i = 0; i < n; i++) {
		b = hi > lo ? (int)((weight[i] - lo) / (hi - lo) * NB) : 0;
		b = b >= NB ? NB - 1 : b;
		cnt[b] += 1.0;
		sum[b] += weight[i];
	}
	for (b = 0; b < NB; b++)
		if (cnt[b] > 0.0) {
			map->fraction[k] = cnt[b] / (double)n;
			map->rel_alpha[k] = sum[b] / cnt[b];
			k++;
		}
	map->n = (unsigned)k;
}
