/*
 * table.c - the flight table: CRC, blob encoding, checks, and the lookup
 * of the attenuation curve alpha_sys(theta) (thesis §5.1).
 */
#include <math.h>
#include <string.h>

#include "fdrfw/table.h"
#include "stray/config.h"

/* No padding: the blob is exactly the fields, 4 bytes each. */
STRAY_STATIC_ASSERT(sizeof(float) == 4, float_is_ieee_single);
STRAY_STATIC_ASSERT(sizeof(struct fdrfw_table) % 4u == 0, table_words);
#define COUNT_M(tf, mf, lo, hi) + 1u
#define COUNT_S(tf, lo, hi) + 1u
/* The CRC last; the scalars from the third word, every one listed. */
STRAY_STATIC_ASSERT((offsetof(struct fdrfw_table, crc32) ==
		     (sizeof(struct fdrfw_table) - 4u)) &&
		    (offsetof(struct fdrfw_table, t_exp_nominal_s) ==
		     (4u * FDRFW_SCALAR_WORD)) &&
		    ((0u FDRFW_MODEL_FIELDS(COUNT_M)
		      FDRFW_TABLE_SCALARS(COUNT_S)) == FDRFW_SCALARS),
		    crc_last_scalars_listed);

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

	/* A table of another version has another length: say so first. */
	if ((len >= 8u) && (buf[0] == 0x46u) && (buf[1] == 0x46u) &&
	    (buf[2] == 0x44u) && (buf[3] == 0x52u) &&
	    ((buf[4] != (uint8_t)FDRFW_TABLE_VERSION) || (buf[5] != 0u) ||
	     (buf[6] != 0u) || (buf[7] != 0u))) {
		return FDRFW_EMAGIC;
	}
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

/* One [min, max] per scalar, in the lists' order (model_map.h, table.h),
 * as many as the table has scalars. */
#define BOUNDS_M(tf, mf, lo, hi) { lo, hi },
#define BOUNDS_S(tf, lo, hi) { lo, hi },

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

/* Every scalar in its closed domain (NaN and inf in none), the window
 * within the sensor, k_px one of its two values. */
static int scalars_check(const struct fdrfw_table *t)
{
	static const float bounds[][2] = {
		FDRFW_MODEL_FIELDS(BOUNDS_M)
		FDRFW_TABLE_SCALARS(BOUNDS_S)
	};
	int rc = (int)FDRFW_OK;
	uint32_t i;

	for (i = 0; (i < FDRFW_SCALARS) && (rc == (int)FDRFW_OK); i++) {
		uint32_t w = FDRFW_SCALAR_WORD + i;
		float v;

		(void)memcpy((void *)&v,
			     (const void *)&((const uint8_t *)t)[4u * w], 4u);
		if (!((v >= bounds[i][0]) && (v <= bounds[i][1]))) {
			rc = FDRFW_EFIELD_WORD(w);
		}
	}
	if ((rc == (int)FDRFW_OK) && !(t->n_pps <= t->n_tot)) {
		rc = FDRFW_EFIELD_OF(n_pps);
	}
	if ((rc == (int)FDRFW_OK) && !k_px_ok(t)) {
		rc = FDRFW_EFIELD_OF(k_px);
	}
	return rc;
}

/* Sample i: angle in [0, 180] and past the previous one, log10 alpha in
 * [floor, 6], the envelope the max of alpha from i on. */
static int sample_check(const struct fdrfw_table *t, uint32_t i)
{
	uint32_t n = t->n_curve;
	int rc = (int)FDRFW_OK;

	if (!((t->theta_deg[i] >= 0.0f) && (t->theta_deg[i] <= 180.0f)) ||
	    ((i > 0u) && !(t->theta_deg[i] > t->theta_deg[i - 1u]))) {
		rc = FDRFW_EFIELD_OF(theta_deg);
	} else if (!((t->log10_alpha[i] >= FDRFW_LOG10_ALPHA_FLOOR) &&
		     (t->log10_alpha[i] <= 6.0f))) {
		rc = FDRFW_EFIELD_OF(log10_alpha);
	} else if (t->log10_alpha_tail[i] != (((i + 1u) < n) ?
		   fmaxf(t->log10_alpha[i], t->log10_alpha_tail[i + 1u]) :
		   t->log10_alpha[i])) {
		rc = FDRFW_EFIELD_OF(log10_alpha_tail);
	} else {
		/* in its domain */
	}
	return rc;
}

/* 2..FDRFW_CURVE_MAX samples, each valid, some alpha > 0 (an all-zero
 * curve attenuates everything: refused). */
static int curve_check(const struct fdrfw_table *t)
{
	uint32_t n = t->n_curve;
	int rc = FDRFW_EFIELD_OF(n_curve);

	if ((n >= 2u) && (n <= (uint32_t)FDRFW_CURVE_MAX)) {
		uint32_t i;

		rc = (int)FDRFW_OK;
		for (i = 0; (i < n) && (rc == (int)FDRFW_OK); i++) {
			rc = sample_check(t, i);
		}
		if ((rc == (int)FDRFW_OK) &&
		    !(t->log10_alpha_tail[0] > FDRFW_LOG10_ALPHA_FLOOR)) {
			rc = FDRFW_EFIELD_OF(log10_alpha);
		}
	}
	return rc;
}

/* The detector (issue 28): a known kind; THESIS flies eq. 2.18 and has
 * no grid; the others FDRFW_DET_MAX nodes a step > 0 apart, ln false
 * stars in [floor, 1000] never falling and P_drs in [0, 1] never rising
 * as the background grows (so an interpolated flag is monotone too). */
static int det_check(const struct fdrfw_table *t)
{
	uint32_t i;
	int rc = (int)FDRFW_OK;

	if (t->detector >= FDRFW_DET_KINDS) {
		rc = FDRFW_EFIELD_OF(detector);
	} else if (t->n_det != ((t->detector == FDRFW_DET_THESIS) ? 0u :
				(uint32_t)FDRFW_DET_MAX)) {
		rc = FDRFW_EFIELD_OF(n_det);
	} else if ((t->n_det > 0u) && !(t->det_du > 0.0f)) {
		rc = FDRFW_EFIELD_OF(det_du);
	} else {
		for (i = 0; (i < t->n_det) && (rc == (int)FDRFW_OK); i++) {
			float l = t->det_ln_false[i];
			float p = t->det_p_drs[i];

			if (!((l >= FDRFW_DET_LN_FLOOR) && (l <= 1e3f)) ||
			    ((i > 0u) && !(l >= t->det_ln_false[i - 1u]))) {
				rc = FDRFW_EFIELD_OF(det_ln_false);
			} else if (!((p >= 0.0f) && (p <= 1.0f)) ||
				   ((i > 0u) && !(p <= t->det_p_drs[i - 1u]))) {
				rc = FDRFW_EFIELD_OF(det_p_drs);
			} else {
				/* in its domain */
			}
		}
	}
	return rc;
}

/* fig. 5.1: the Sun's exclusion angle is where the envelope falls to
 * alpha_req: the envelope reaches alpha_req on the boresight (so the Sun
 * there is excluded) and no further than the angle claimed (a looser
 * bound on the far side: a zero sample's log floor may fall faster than
 * libstray's linear step to 0, never slower). */
static int exclusion_check(const struct fdrfw_table *t)
{
	float req = t->alpha_req_sun;
	int rc = (int)FDRFW_OK;

	if (!(fdrfw_envelope_at(t, 0.0f) >= req) ||
	    !(fdrfw_envelope_at(t, t->exclusion_sun_deg) <= (1.001f * req))) {
		rc = FDRFW_EFIELD_OF(exclusion_sun_deg);
	}
	return rc;
}

int fdrfw_table_check(const struct fdrfw_table *t)
{
	int rc;

	if ((t->magic != FDRFW_TABLE_MAGIC) ||
	    (t->version != FDRFW_TABLE_VERSION)) {
		rc = (int)FDRFW_EMAGIC;
	} else if (table_crc(t) != t->crc32) {
		rc = (int)FDRFW_ECRC;
	} else {
		rc = scalars_check(t);
		if (rc == (int)FDRFW_OK) {
			rc = det_check(t);
		}
		if (rc == (int)FDRFW_OK) {
			rc = curve_check(t);
		}
		if (rc == (int)FDRFW_OK) {
			rc = exclusion_check(t);
		}
	}
	return rc;
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
