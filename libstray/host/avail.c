/*
 * avail.c - outage statistics of exclusion masks; zonal albedo.
 */
#include <math.h>
#include <string.h>

#include "stray/avail.h"

static const double bin_edge_s[STRAY_AVAIL_BINS - 1] = { 60, 300, 900, 3600 };

static void close_outage(struct stray_avail_stats *s, double d)
{
	int b = 0;

	s->outages++;
	s->mean_outage_s += d;
	if (d > s->longest_outage_s)
		s->longest_outage_s = d;
	while (b < STRAY_AVAIL_BINS - 1 && d >= bin_edge_s[b])
		b++;
	s->hist[b]++;
}

void stray_avail_summarise(const uint8_t *mask, size_t n, double step_s,
			   struct stray_avail_stats *s)
{
	size_t i, run = 0, avail = 0, sun = 0, moon = 0, earth = 0;

	memset(s, 0, sizeof(*s));
	for (i = 0; i < n; i++) {
		uint8_t m = mask[i];

		if (m & STRAY_AVAIL_UNCOVERED) {
			s->uncovered++;
			if (run)
				close_outage(s, (double)run * step_s);
			run = 0;
			continue;
		}
		sun += (m & STRAY_AVAIL_SUN) != 0;
		moon += (m & STRAY_AVAIL_MOON) != 0;
		earth += (m & STRAY_AVAIL_EARTH) != 0;
		if (m & STRAY_AVAIL_BLIND) {
			run++;
			continue;
		}
		avail++;
		if (run)
			close_outage(s, (double)run * step_s);
		run = 0;
	}
	if (run)
		close_outage(s, (double)run * step_s);
	s->epochs = n - s->uncovered;
	if (s->epochs) {
		double c = (double)s->epochs;

		s->available_frac = (double)avail / c;
		s->sun_frac = (double)sun / c;
		s->moon_frac = (double)moon / c;
		s->earth_frac = (double)earth / c;
	}
	if (s->outages)
		s->mean_outage_s /= (double)s->outages;
}

double stray_albedo_zonal_sin(double x, double sin_dec)
{
	double p2 = 0.5 * (3.0 * x * x - 1.0);
	double a = 0.30 + 0.12 * p2 -
		   0.04 * x * sin_dec / sin(23.44 * 3.14159265358979324 / 180.0);

	return a < 0.05 ? 0.05 : a > 0.9 ? 0.9 : a;
}

double stray_albedo_zonal(double lat_rad, double dec_rad)
{
	return stray_albedo_zonal_sin(sin(lat_rad), sin(dec_rad));
}
