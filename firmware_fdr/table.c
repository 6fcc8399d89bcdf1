/*
 * table.c - the flight table: CRC, blob encoding, checks, and the lookup
 * of the attenuation curve alpha_sys(theta) (thesis §5.1).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "fdrfw/table.h"
#include "stray/config.h"

/* No padding: the blob is exactly the fields, 4 bytes each. */
STRAY_STATIC_ASSERT(sizeof(float) == 4, float_is_ieee_single);
STRAY_STATIC_ASSERT(sizeof(struct fdrfw_table) % 4u == 0, table_words);
STRAY_STATIC_ASSERT(offsetof(struct fdrfw_table, crc32) ==
		    sizeof(struct fdrfw_table) - 4u, crc_is_last);

uint32_t fdrfw_crc32(uint32_t crc, const uint8_t *buf, size_t len)
{
	uint32_t c = ~crc;
	size_t i;
	unsigned k;

	for (i = 0; i < len; i++) {
		c ^= buf[i];
		for (k = 0; k < 8u; k++) {	/* bitwise: no 1 KiB table */
			c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
		}
	}
	return ~c;
}

/* Word i of the table as stored (its bit pattern, float or integer). */
static uint32_t word_at(const struct fdrfw_table *t, size_t i)
{
	uint32_t w;

	memcpy(&w, (const uint8_t *)t + 4u * i, 4u);
	return w;
}

void fdrfw_table_serialize(const struct fdrfw_table *t,
			   uint8_t out[FDRFW_BLOB_SIZE])
{
	size_t i;

	for (i = 0; i < FDRFW_TABLE_WORDS; i++) {
		uint32_t w = word_at(t, i);

		out[4u * i] = (uint8_t)(w & 0xFFu);
		out[4u * i + 1u] = (uint8_t)((w >> 8) & 0xFFu);
		out[4u * i + 2u] = (uint8_t)((w >> 16) & 0xFFu);
		out[4u * i + 3u] = (uint8_t)(w >> 24);
	}
}

/* CRC of every word but the last, fed little-endian (as in the blob). */
static uint32_t table_crc(const struct fdrfw_table *t)
{
	uint32_t crc = 0;
	size_t i;

	for (i = 0; i + 1u < FDRFW_TABLE_WORDS; i++) {
		uint32_t w = word_at(t, i);
		uint8_t b[4];

		b[0] = (uint8_t)(w & 0xFFu);
		b[1] = (uint8_t)((w >> 8) & 0xFFu);
		b[2] = (uint8_t)((w >> 16) & 0xFFu);
		b[3] = (uint8_t)(w >> 24);
		crc = fdrfw_crc32(crc, b, 4u);
	}
	return crc;
}

void fdrfw_table_seal(struct fdrfw_table *t)
{
	t->crc32 = table_crc(t);
}

int fdrfw_table_parse(const uint8_t *buf, size_t len, struct fdrfw_table *t)
{
	size_t i;

	if (len != FDRFW_BLOB_SIZE)
		return FDRFW_ESIZE;
	for (i = 0; i < FDRFW_TABLE_WORDS; i++) {
		const uint8_t *p = buf + 4u * i;
		uint32_t w = (uint32_t)p[0] | ((uint32_t)p[1] << 8) |
			     ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);

		memcpy((uint8_t *)t + 4u * i, &w, 4u);
	}
	return FDRFW_OK;
}

static int in_range(float v, float lo, float hi)
{
	return isfinite(v) && v >= lo && v <= hi;
}

static int positive(float v)
{
	return isfinite(v) && v > 0.0f;
}

static int at_least_one(float v)
{
	return in_range(v, 1.0f, FLT_MAX);
}

static int probability(float v)
{
	return in_range(v, 1e-6f, 0.999999f);
}

int fdrfw_table_is_thesis(const struct fdrfw_table *t)
{
	return t->k_px == 1.0f;
}

/* k_px is the thesis's 1 or A_cs / (n_tot A_px) of the table's own
 * fields (eq. 2.3 with eq. 3.11-3.12's alpha), to float rounding. */
static int k_px_ok(const struct fdrfw_table *t)
{
	float k = t->a_cs_m2 / (t->n_tot * t->a_px_m2);

	return fdrfw_table_is_thesis(t) ||
	       (fabsf(t->k_px - k) <= (1e-5f * k));
}

/* The FDR model fields, each in its domain (model_map.h), and the
 * sources. */
static int model_fields_ok(const struct fdrfw_table *t)
{
#define FDRFW_FIELD_OK(tf, mf, domain) domain(t->tf) &&
	return FDRFW_MODEL_FIELDS(FDRFW_FIELD_OK)
	       (t->n_pps <= t->n_tot) && k_px_ok(t) && isfinite(t->i_sdt_e) &&
	       positive(t->fdr_tolerated) && positive(t->f_sun_ph_s_m2) &&
	       positive(t->f_moon_full_ph_s_m2) &&
	       isfinite(t->moon_full_mag) &&
	       in_range(t->earth_albedo, 0.0f, 1.0f) &&
	       in_range(t->fov_half_deg, 0.01f, 89.0f) &&
	       in_range(t->hysteresis_deg, 0.0f, 10.0f);
}

/* Angles increasing in [0, 180], alpha finite, the envelope consistent. */
static int curve_ok(const struct fdrfw_table *t)
{
	uint32_t i, n = t->n_curve;

	if (n < 2u || n > FDRFW_CURVE_MAX)
		return 0;
	for (i = 0; i < n; i++) {
		if (!in_range(t->theta_deg[i], 0.0f, 180.0f) ||
		    !in_range(t->log10_alpha[i], FDRFW_LOG10_ALPHA_FLOOR, 6.0f))
			return 0;
		if (i > 0u && !(t->theta_deg[i] > t->theta_deg[i - 1u]))
			return 0;
		if (t->log10_alpha_tail[i] != (i + 1u < n ?
		    fmaxf(t->log10_alpha[i], t->log10_alpha_tail[i + 1u]) :
		    t->log10_alpha[i]))
			return 0;
	}
	return 1;
}

int fdrfw_table_check(const struct fdrfw_table *t)
{
	if (t->magic != FDRFW_TABLE_MAGIC || t->version != FDRFW_TABLE_VERSION)
		return FDRFW_EMAGIC;
	if (table_crc(t) != t->crc32)
		return FDRFW_ECRC;
	if (!model_fields_ok(t) || !curve_ok(t))
		return FDRFW_ERANGE;
	return FDRFW_OK;
}

/* First sample index with theta_deg > x, in [1, n-1] for x inside. */
static uint32_t segment_after(const struct fdrfw_table *t, float x)
{
	uint32_t lo = 0, hi = t->n_curve - 1u;

	while (hi - lo > 1u) {	/* bisection: at most log2(n) steps */
		uint32_t mid = lo + (hi - lo) / 2u;

		if (t->theta_deg[mid] <= x)
			lo = mid;
		else
			hi = mid;
	}
	return hi;
}

/* log10 alpha at theta, linear in theta (libstray's log-linear rule). */
static float log10_alpha_at(const struct fdrfw_table *t, float theta_deg,
			    uint32_t *next)
{
	uint32_t n = t->n_curve, i;
	float f;

	if (theta_deg <= t->theta_deg[0]) {
		*next = 1u;
		return t->log10_alpha[0];
	}
	if (theta_deg >= t->theta_deg[n - 1u]) {
		*next = n;
		return t->log10_alpha[n - 1u];
	}
	i = segment_after(t, theta_deg);
	*next = i;
	f = (theta_deg - t->theta_deg[i - 1u]) /
	    (t->theta_deg[i] - t->theta_deg[i - 1u]);
	return t->log10_alpha[i - 1u] +
	       f * (t->log10_alpha[i] - t->log10_alpha[i - 1u]);
}

static float alpha_of_log10(float l)
{
	return l <= FDRFW_LOG10_ALPHA_FLOOR ? 0.0f : powf(10.0f, l);
}

float fdrfw_alpha_at(const struct fdrfw_table *t, float theta_deg)
{
	uint32_t next;

	return alpha_of_log10(log10_alpha_at(t, theta_deg, &next));
}

float fdrfw_envelope_at(const struct fdrfw_table *t, float theta_deg)
{
	uint32_t next;
	float l = log10_alpha_at(t, theta_deg, &next);

	/* Samples strictly beyond theta: log10_alpha_tail[next]. */
	if (next < t->n_curve && t->log10_alpha_tail[next] > l)
		l = t->log10_alpha_tail[next];
	return alpha_of_log10(l);
}
