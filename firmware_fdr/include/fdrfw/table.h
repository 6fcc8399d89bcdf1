/*
 * table.h - the flight configuration table of firmware_fdr.
 *
 * Generated on the ground by `stray firmware-table` from an attenuation
 * curve and a sensor (thesis §2.3, §5.1), and carried to the module two
 * ways: as const C source (in flash) or as a binary blob (uploaded).  Both
 * carry a CRC-32 that fdrfw_table_check verifies before the table is used.
 *
 * Every field is 32 bits (uint32_t or IEEE-754 float), so the table has no
 * padding and its blob is the fields in order, each little-endian: the
 * same bytes on the host and on the Cortex-M4.
 */
#ifndef FDRFW_TABLE_H
#define FDRFW_TABLE_H

#include <stddef.h>
#include <stdint.h>

#include "fdrfw/model_map.h"

#define FDRFW_TABLE_MAGIC 0x52444646u	/* "FFDR" little-endian */
/* 2: k_px (docs/normalisation.md); 3: the named detector's grid and
 * z_drs (issue 28).  Another version is refused (FDRFW_EMAGIC). */
#define FDRFW_TABLE_VERSION 3u
#define FDRFW_CURVE_MAX 128		/* samples of the attenuation curve */

/*
 * The named detector (stray/detector.h's enum, as a table word): THESIS
 * flies eq. 2.18 by libstray's core on board, as before; the others fly
 * their validated models tabulated on the ground over the background
 * I_px, FDRFW_DET_MAX nodes (table_build.h: where they lie).
 */
#define FDRFW_DET_THESIS 0u
#define FDRFW_DET_KINDS 4u
#define FDRFW_DET_MAX 72
/* ln of false stars per image stored for "none" (1e-30, the vectors'
 * floor): a rate at or below it is reported as none. */
#define FDRFW_DET_LN_FLOOR (-69.0775528f)

/* alpha = 0 in a curve is stored as this log10 (a floor, not -inf). */
#define FDRFW_LOG10_ALPHA_FLOOR (-40.0f)

/*
 * The table's scalars after the model constants, in order, as
 * X(field, min, max): the same closed physical domains as model_map.h's
 * (NaN and inf outside every one).  I_sdt: 1 .. 10^9 e- in a window (and
 * equal to eq. 2.16 of the table's own model, checked at init); a tolerated
 * rate of 1e-9 .. 10^4 false stars per image; the Sun's photon flux from
 * beyond Jupiter to inside Mercury's orbit in any passband (about 4e21 at
 * 1 AU over the whole spectrum), the full Moon's 10^10 .. 10^18 (about
 * 2e15) and its magnitude -15 .. -10 (V: -12.7); a field 0.01 .. 89 deg;
 * the Sun's alpha_req 1e-30 .. 1e6 (the curve's own range) and its
 * exclusion angle > 0: a table whose Sun never blinds the tracker is no
 * flight table (an all-zero curve gives 0 deg).  z_drs = Q^-1(Pr_drs) of
 * eq. 2.16, solved on the ground (Pr_drs in [1e-6, 1 - 1e-6]: |z| < 4.8)
 * and checked on board by Q(z); tetra3's k sigma (0 for the others);
 * the detector grid's ln I_px at node 0 (I_px from e^-60 to e^60 e-) and
 * its step (0 for THESIS, else ln 10 / FDRFW_DET_PER_DECADE).
 */
#define FDRFW_TABLE_SCALARS(X) \
	X(i_sdt_e, 1.0f, 1e9f) \
	X(fdr_tolerated, 1e-9f, 1e4f) \
	X(f_sun_ph_s_m2, 1e17f, 1e23f) \
	X(f_moon_full_ph_s_m2, 1e10f, 1e18f) \
	X(moon_full_mag, -15.0f, -10.0f) \
	X(earth_albedo, 0.0f, 1.0f) \
	X(fov_half_deg, 0.01f, 89.0f) \
	X(hysteresis_deg, 0.0f, 10.0f) \
	X(alpha_req_sun, 1e-30f, 1e6f) \
	X(exclusion_sun_deg, 1e-3f, 180.0f) \
	X(z_drs, -5.0f, 5.0f) \
	X(detector_sigma, 0.0f, 20.0f) \
	X(det_u0, -60.0f, 60.0f) \
	X(det_du, 0.0f, 2.0f)

struct fdrfw_table {
	uint32_t magic;
	uint32_t version;
	uint32_t n_curve;		/* samples used, 2..FDRFW_CURVE_MAX */
	/* FDR model constants, thesis eq. 2.3-2.18 (stray_fdr_model), one
	 * float each in model_map.h's order: t_exp_nominal_s (the exposure
	 * I_sdt was computed for), a_px_m2, k_px (eq. 2.3's per-pixel
	 * factor: 1, the thesis, or A_cs / (n_tot A_px), checked), a_cs_m2,
	 * n_pps, n_tot, pr_drs, f_drs_ph_s_m2. */
#define FDRFW_TABLE_FIELD(tf, mf, lo, hi) float tf;
	FDRFW_MODEL_FIELDS(FDRFW_TABLE_FIELD)
	float i_sdt_e;			/* I_sdt at t_exp_nominal_s, eq. 2.16 */
	float fdr_tolerated;		/* false stars per image allowed */
	/* Sources (photon fluxes in the sensor passband, eq. 2.1). */
	float f_sun_ph_s_m2;
	float f_moon_full_ph_s_m2;
	float moon_full_mag;		/* for the phase law */
	float earth_albedo;		/* Lambertian, 0..1 */
	/* Geometry. */
	float fov_half_deg;
	float hysteresis_deg;		/* flags clear this far past the edge */
	/* Ground results kept for telemetry and checks (not used per frame). */
	float alpha_req_sun;		/* fig. 2.7 at nominal exposure */
	float exclusion_sun_deg;	/* fig. 5.1 */
	/* Version 3 (issue 28). */
	float z_drs;			/* Q^-1(Pr_drs), eq. 2.16 */
	float detector_sigma;		/* TETRA3's k; 0 for the others */
	float det_u0;			/* ln I_px [e-] of the grid's node 0 */
	float det_du;			/* the grid's step in ln I_px */
	uint32_t detector;		/* FDRFW_DET_THESIS, or the kind */
	uint32_t n_det;			/* grid nodes: 0 (THESIS), else
					 * FDRFW_DET_MAX */
	/* The system attenuation curve alpha_sys(theta). */
	float theta_deg[FDRFW_CURVE_MAX];
	float log10_alpha[FDRFW_CURVE_MAX];
	/* max over j >= i of log10_alpha[j]: the exclusion envelope. */
	float log10_alpha_tail[FDRFW_CURVE_MAX];
	/* The detector's models at nominal exposure, node i at ln I_px =
	 * det_u0 + i det_du (I_px of every body's light, eq. 2.3): ln of its
	 * false stars per image (floored at FDRFW_DET_LN_FLOOR, never
	 * falling) and the DRS's detection probability (never rising). */
	float det_ln_false[FDRFW_DET_MAX];
	float det_p_drs[FDRFW_DET_MAX];
	uint32_t crc32;			/* CRC-32 of every byte before it */
};

#define FDRFW_TABLE_WORDS (sizeof(struct fdrfw_table) / 4u)
#define FDRFW_BLOB_SIZE (FDRFW_TABLE_WORDS * 4u)

/* The scalars of both lists: the words from FDRFW_SCALAR_WORD (after
 * n_curve) to the detector's kind. */
#define FDRFW_SCALAR_WORD 3u
#define FDRFW_SCALARS \
	(((uint32_t)offsetof(struct fdrfw_table, detector) / 4u) - \
	 FDRFW_SCALAR_WORD)

enum fdrfw_status {
	FDRFW_OK = 0,
	FDRFW_EMAGIC,	/* not a table, or wrong version */
	FDRFW_ESIZE,	/* blob of the wrong length */
	FDRFW_ECRC,	/* CRC mismatch: corrupted */
	FDRFW_ERANGE,	/* the model the fields make is not valid */
	FDRFW_EINPUT	/* a frame's inputs are invalid */
};

/*
 * FDRFW_EFIELD + the word index of a field in the table: that field is
 * outside its domain or inconsistent with the others (a valid CRC is not a
 * valid table); table_build.h names it.  FDRFW_EFIELD_WORD for the field
 * at word w, FDRFW_EFIELD_OF for the field named (a struct member: not
 * parenthesised).
 */
#define FDRFW_EFIELD 16
#define FDRFW_EFIELD_WORD(w) (FDRFW_EFIELD + (int)(w))
#define FDRFW_EFIELD_OF(field) \
	(FDRFW_EFIELD + ((int)offsetof(struct fdrfw_table, field) / 4))

/* CRC-32 (IEEE 802.3, reflected, poly 0xEDB88320), continuing from crc. */
uint32_t fdrfw_crc32(uint32_t crc, const uint8_t *buf, size_t len);

/* The table's blob: every word little-endian, in field order. */
void fdrfw_table_serialize(const struct fdrfw_table *t,
			   uint8_t out[FDRFW_BLOB_SIZE]);

/* Set t->crc32 from the other fields (ground side). */
void fdrfw_table_seal(struct fdrfw_table *t);

/* Decode a blob into *t (no check of its contents beyond the length);
 * FDRFW_EMAGIC for a table of another version (its length differs). */
int fdrfw_table_parse(const uint8_t *buf, size_t len, struct fdrfw_table *t);

/*
 * Magic, version, CRC, then every field in its domain (FDRFW_EFIELD_OF
 * the first that is not), n_pps <= n_tot, k_px, and the curve; a table that
 * fails is never used.  fdrfw_init adds the checks that need the model
 * (I_sdt, alpha_req, the Sun on the boresight).  Returns an enum
 * fdrfw_status.
 */
int fdrfw_table_check(const struct fdrfw_table *t);

/*
 * The table's normalisation (docs/normalisation.md): 1 when k_px is the
 * thesis's 1, 0 when it is A_cs / (n_tot A_px) of its own fields.
 */
int fdrfw_table_is_thesis(const struct fdrfw_table *t);

/* alpha_sys(theta) from the table: log-linear, clamped at both ends. */
float fdrfw_alpha_at(const struct fdrfw_table *t, float theta_deg);

/*
 * The exclusion envelope at theta: max(alpha(theta), alpha of every sample
 * beyond theta).  alpha_req <= envelope(theta) exactly when theta lies
 * before stray_exclusion_angle(curve, alpha_req) (fig. 5.1's rule that
 * all further off-axis attenuations lie beneath alpha_req).
 */
float fdrfw_envelope_at(const struct fdrfw_table *t, float theta_deg);

#endif /* FDRFW_TABLE_H */
