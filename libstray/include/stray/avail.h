/*
 * avail.h - tracker availability along a mission: outage statistics of
 * per-epoch exclusion masks, and the Earth's albedo by latitude and season.
 */
#ifndef STRAY_AVAIL_H
#define STRAY_AVAIL_H

#include <stddef.h>
#include <stdint.h>

/* Mask bits per epoch (the flight module's flag bits 0-2 and 7). */
#define STRAY_AVAIL_SUN 0x01u
#define STRAY_AVAIL_MOON 0x02u
#define STRAY_AVAIL_EARTH 0x04u
#define STRAY_AVAIL_INVALID 0x80u
/* Not flown: the epoch is in a gap of the orbit or attitude records. */
#define STRAY_AVAIL_UNCOVERED 0x40u
#define STRAY_AVAIL_BLIND (STRAY_AVAIL_SUN | STRAY_AVAIL_MOON | \
			   STRAY_AVAIL_EARTH | STRAY_AVAIL_INVALID)

/* Outage duration bins [s]: < 60, < 300, < 900, < 3600, longer. */
#define STRAY_AVAIL_BINS 5

struct stray_avail_stats {
	size_t epochs;		/* covered: every fraction is of these */
	size_t uncovered;	/* STRAY_AVAIL_UNCOVERED epochs */
	double available_frac;	/* no blinding bit */
	double sun_frac, moon_frac, earth_frac;	/* each bit (may overlap) */
	size_t outages;		/* maximal runs of blind epochs */
	double longest_outage_s, mean_outage_s;
	size_t hist[STRAY_AVAIL_BINS];
};

/*
 * Statistics of n epochs step_s apart: an outage of k consecutive blind
 * epochs lasts k step_s (each epoch stands for its step).  Uncovered
 * epochs count for nothing (neither available nor blind) and end an
 * outage: what happened in a gap is not known.
 */
void stray_avail_summarise(const uint8_t *mask, size_t n, double step_s,
			   struct stray_avail_stats *s);

/*
 * Top-of-atmosphere albedo at geographic latitude lat [rad] when the
 * subsolar latitude is dec [rad]: the documented fallback of
 * docs/availability.md, a(x) = 0.30 + 0.12 P2(x) - 0.04 x sin(dec)/sin(eps),
 * x = sin(lat), eps = 23.44 deg; its area mean is 0.30 in every season.
 */
double stray_albedo_zonal(double lat_rad, double dec_rad);

/* The same from x = sin(lat) and sin(dec), for callers that have them. */
double stray_albedo_zonal_sin(double x, double sin_dec);

#endif /* STRAY_AVAIL_H */
