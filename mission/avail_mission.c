/*
 * avail_mission.c - `stray availability`: the mission loaded (OEM, AEM,
 * heads and their tables), and the flight module flown per head at every
 * epoch the files cover.
 */
#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mission/avail_heads.h"
#include "mission/avail_mission.h"
#include "fdrfw/earth.h"
#include "fdrfw/ephem.h"
#include "fdrfw/table_build.h"
#include "fdrfw/vec.h"
#include "mission/flight_table.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define RAD2DEG 57.2957795130823209

/* The detector asked for (--detector), checked against the table
 * (issue 28: a table read as another detector is refused). */
static int head_detector(const struct mission_args *a,
			 const struct fdrfw_table *t, const char *path,
			 struct stray_error *err)
{
	enum stray_detector_kind k;

	if (!a->detector)
		return STRAY_OK;
	if (stray_detector_parse(a->detector, &k, err) != STRAY_OK)
		return STRAY_EINVAL;
	return fdrfw_table_detector_check(t, k, a->detector_sigma, path, err);
}

static int load_heads(const struct mission_args *a, const char *path,
		      struct mission *m, struct stray_error *err)
{
	struct avail_head_spec spec[AVAIL_HEADS_MAX];
	char *buf;
	size_t len, n, i;
	int rc = stray_file_read(path, &buf, &len, err);

	if (rc != STRAY_OK)
		return rc;
	rc = avail_heads_parse(buf, len, path, spec, &n, err);
	free(buf);
	for (i = 0; rc == STRAY_OK && i < n; i++) {
		struct mission_head *hd = &m->head[i];

		memcpy(hd->name, spec[i].name, sizeof(hd->name));
		memcpy(hd->m_bs, spec[i].m_bs, sizeof(hd->m_bs));
		if ((rc = flight_table_load(spec[i].table, &hd->table, err)) ==
		    STRAY_OK &&
		    (rc = head_detector(a, &hd->table, spec[i].table, err)) ==
		    STRAY_OK)
			m->n_heads = i + 1;
	}
	return rc;
}

int mission_load(const struct mission_args *a, struct mission *m,
		 struct stray_error *err)
{
	double t1;
	size_t h;
	int rc;

	/* Earth orientation first: the readers convert Earth-fixed frames
	 * as they read */
	if (a->iers && (rc = stray_ccsds_eop_load(a->iers, err)) != STRAY_OK)
		return rc;
	if (m->oem_text)	/* just written: fly that, not the disk */
		rc = stray_oem_parse(m->oem_text, m->oem_len, a->oem, &m->oem, err);
	else
		rc = stray_oem_read(a->oem, &m->oem, err);
	if (rc != STRAY_OK)
		return rc;
	if (m->aem_text)
		rc = stray_aem_parse(m->aem_text, m->aem_len, a->aem, &m->aem, err);
	else
		rc = stray_aem_read(a->aem, &m->aem, err);
	if (rc != STRAY_OK || (rc = load_heads(a, a->heads, m, err)) != STRAY_OK)
		return rc;
	/* the span the segments cover (a hole inside is reported, not flown) */
	m->t0 = fmax(m->oem.cover.t0, m->aem.cover.t0);
	t1 = fmin(m->oem.cover.t1, m->aem.cover.t1);
	t1 = fmin(t1, m->t0 + a->hours * 3600.0);
	if (!(t1 > m->t0))
		return stray_error_at(err, STRAY_EINVAL, a->aem, 0, "START_TIME",
				      "the OEM and AEM spans do not overlap");
	m->step_s = a->step_s;
	m->n = (size_t)floor((t1 - m->t0) / a->step_s + 1e-9) + 1;
	m->any_mask = calloc(m->n, 1);
	m->albedo = calloc(m->n, sizeof(float));
	if (!m->any_mask || !m->albedo)
		return stray_error_set(err, STRAY_ENOMEM, "epochs", NULL);
	m->n_sky = m->n < MISSION_SKY_MAX ? m->n : MISSION_SKY_MAX;
	for (h = 0; h < m->n_heads; h++) {
		struct mission_head *hd = &m->head[h];
		int b, c;

		hd->mask = calloc(m->n, 1);
		hd->stars = calloc(m->n, sizeof(float));
		if (!hd->mask || !hd->stars)
			return stray_error_set(err, STRAY_ENOMEM, "epochs", NULL);
		for (b = 0; b < 3; b++)
			for (c = 0; c < 2; c++)
				if (!(hd->sky[b][c] = calloc(m->n_sky, sizeof(double))))
					return stray_error_set(err, STRAY_ENOMEM, "sky", NULL);
		if (fdrfw_init(&hd->ctx, &hd->table) != FDRFW_OK)
			return stray_error_at(err, STRAY_EINVAL, a->heads, 0,
					      "table", "the flight module refuses it");
		{	/* the one exclusion verdict (libstray) */
			struct stray_exclusion ex;

			if ((rc = fdrfw_table_sun_verdict(&hd->table, &ex,
							  err)) != STRAY_OK)
				return rc;
			hd->sun_excluded = ex.excluded;
			hd->sun_reason = ex.reason;
		}
	}
	return STRAY_OK;
}

void mission_free(struct mission *m)
{
	size_t h;
	int b, c;

	stray_oem_free(&m->oem);
	stray_aem_free(&m->aem);
	stray_ccsds_eop_clear();
	free(m->oem_text);
	free(m->aem_text);
	for (h = 0; h < MISSION_HEADS_MAX; h++) {
		free(m->head[h].mask);
		free(m->head[h].stars);
		for (b = 0; b < 3; b++)
			for (c = 0; c < 2; c++)
				free(m->head[h].sky[b][c]);
	}
	free(m->any_mask);
	free(m->albedo);
}

void mission_fw_q(const double m[3][3], float q[4])
{
	double c[4];

	/* M(q) of 504.0 is R(q)^T of the module's Hamilton R: conjugate */
	stray_dcm_q(m, c);
	q[0] = (float)c[0];
	q[1] = (float)-c[1];
	q[2] = (float)-c[2];
	q[3] = (float)-c[3];
}

double mission_cap_albedo(const float pos_km[3], const float sun[3])
{
	struct fdrfw_earth_cap cap;
	double sw = 0.0, swa = 0.0, sin_dec = fmax(-1.0, fmin(1.0, sun[2]));
	double r2 = 0.0, us = 0.0, rr = (double)FDRFW_EARTH_RADIUS_KM;
	unsigned k;
	int i;

	if (!fdrfw_earth_cap(pos_km, sun, &cap))
		return 0.3;
	for (i = 0; i < 3; i++) {
		r2 += (double)pos_km[i] * pos_km[i];
		us += (double)pos_km[i] * sun[i];
	}
	/* All the cap in the night: every node's ground point is within
	 * acos(R / r) of the sub-spacecraft point, so the Sun's elevation
	 * there is below zero when the Sun is over 90 deg + that from the
	 * zenith (1e-3 is far above the nodes' float rounding). */
	if (us / sqrt(r2) < -sqrt(1.0 - rr * rr / r2) - 1e-3)
		return 0.3;
	for (k = 0; k < FDRFW_EARTH_NODES; k++) {
		struct fdrfw_earth_node nd;
		double pd = 0.0, d, p[3], w;

		fdrfw_earth_node(&cap, k, &nd);
		if (!(nd.cos_sun > 0.0f))
			continue;
		for (i = 0; i < 3; i++)
			pd += (double)pos_km[i] * nd.dir[i];
		/* the surface point along the node's direction */
		d = -pd - sqrt(fmax(0.0, pd * pd - (r2 - rr * rr)));
		for (i = 0; i < 3; i++)
			p[i] = pos_km[i] + d * nd.dir[i];
		w = (double)nd.cos_sun * nd.omega_sr;
		sw += w;
		swa += w * stray_albedo_zonal_sin(fmax(-1.0, fmin(1.0,
				p[2] / sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]))),
				sin_dec);
	}
	return sw > 0.0 ? swa / sw : 0.3;
}

/* Direction d (inertial) in the head's frame, as a sky-plot point:
 * azimuthal equidistant about the boresight [deg]. */
static void sky_point(const double mis[3][3], const double d[3], double *x,
		      double *y)
{
	double s[3], th, ph, n;
	int i;

	for (i = 0; i < 3; i++)
		s[i] = mis[i][0] * d[0] + mis[i][1] * d[1] + mis[i][2] * d[2];
	n = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
	th = acos(fmax(-1.0, fmin(1.0, s[2] / n))) * RAD2DEG;
	ph = atan2(s[1], s[0]);
	*x = th * cos(ph);
	*y = th * sin(ph);
}

static void sky_sample(struct mission_head *hd, size_t j, const double mis[3][3],
		       const double r[3], const float sun[3], int32_t t)
{
	float mo[3];
	double s[3], mm[3], nad[3], b[3], e[3], rn, rho, ang, c;
	int i;

	fdrfw_moon_pos_km(t, mo);
	rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	for (i = 0; i < 3; i++) {
		s[i] = sun[i];
		mm[i] = mo[i] - r[i];
		nad[i] = -r[i] / rn;
		b[i] = mis[2][i];
	}
	sky_point(mis, s, &hd->sky[0][0][j], &hd->sky[0][1][j]);
	sky_point(mis, mm, &hd->sky[1][0][j], &hd->sky[1][1][j]);
	/* the Earth's limb nearest the boresight: nadir turned by rho */
	rho = asin(FDRFW_EARTH_RADIUS_KM / rn);
	c = b[0] * nad[0] + b[1] * nad[1] + b[2] * nad[2];
	ang = acos(fmax(-1.0, fmin(1.0, c)));
	for (i = 0; i < 3; i++)
		e[i] = ang > 1e-9 ? (sin(ang - rho) * nad[i] +
				      sin(rho) * b[i]) / sin(ang) : nad[i];
	sky_point(mis, e, &hd->sky[2][0][j], &hd->sky[2][1][j]);
}

/* The flight module's flag bits 0-7 (fdrfw/fdrfw.h), as named columns. */
static const char *const flag_name[8] = {
	"sun_excluded", "moon_excluded", "earth_excluded", "sun_in_fov",
	"moon_in_fov", "earth_in_fov", "sun_eclipsed", "input_invalid" };

static FILE *csv_open(const struct mission_args *a, const struct mission *m,
		      struct stray_file_out *out, struct stray_error *err)
{
	size_t h;
	int k;

	if (!a->csv)
		return NULL;
	if (stray_file_open_atomic(out, a->csv, err) != STRAY_OK)
		return NULL;
	fprintf(out->f, "# stray availability: flight module per head along %s / %s\nt_s,albedo",
		a->oem, a->aem);
	for (h = 0; h < m->n_heads; h++)
		fprintf(out->f, ",%s_flags,%s_sun_deg,%s_false_stars",
			m->head[h].name, m->head[h].name, m->head[h].name);
	/* issue 32: a notebook reads the time and the flags by name */
	fputs(",any_available,utc", out->f);
	for (h = 0; h < m->n_heads; h++)
		for (k = 0; k < 8; k++)
			fprintf(out->f, ",%s_%s", m->head[h].name,
				flag_name[k]);
	fputc('\n', out->f);
	return out->f;
}

/* Epochs are taken in blocks: what every head shares (orbit, attitude,
 * Sun, Moon, albedo) is made for a block in chunks of epochs, then each
 * head flies the block in order (its flags latch from frame to frame).
 * A block's heads fly while the next block's chunks are made, all as
 * tasks, so two cores share three heads evenly. */
#define BLOCK 4096
#define CHUNK 512

struct block {
	double r[BLOCK][3], mib[BLOCK][3][3];
	float sun[BLOCK][3], moon[BLOCK][3];
	int32_t t_tt[BLOCK];
	int bad[BLOCK];
	uint32_t flags[MISSION_HEADS_MAX][BLOCK];
	float sun_deg[MISSION_HEADS_MAX][BLOCK];
};

/* The albedo is made every ALBEDO_S seconds of the span (the ground
 * track moves ~450 km in a minute) and held between. */
#define ALBEDO_S 60.0

static size_t albedo_every(const struct mission *m)
{
	return m->step_s >= ALBEDO_S ? 1 : (size_t)(ALBEDO_S / m->step_s);
}

/* Epochs j0 .. j1-1 of the block starting at epoch i0. */
static void shared_chunk(struct mission *m, struct block *b, size_t i0,
			 size_t j0, size_t j1)
{
	size_t every = albedo_every(m), j;

	for (j = j0; j < j1; j++) {
		double t = m->t0 + (double)(i0 + j) * m->step_s, v[3], q[4];
		float pos[3], mo[3];
		int k;

		b->bad[j] = stray_oem_state(&m->oem, t, b->r[j], v) != STRAY_OK ||
			    stray_aem_attitude(&m->aem, t, q) != STRAY_OK;
		if (b->bad[j])
			continue;
		b->t_tt[j] = (int32_t)lround(t);
		for (k = 0; k < 3; k++)
			pos[k] = (float)b->r[j][k];
		fdrfw_sun_dir(b->t_tt[j], b->sun[j]);
		/* the Moon from the spacecraft, as the module's ephemeris
		 * mode makes it, once for every head */
		fdrfw_moon_pos_km(b->t_tt[j], mo);
		for (k = 0; k < 3; k++)
			mo[k] -= pos[k];
		(void)fdrfw_unit(mo, b->moon[j]);
		if ((i0 + j) % every == 0)
			m->albedo[i0 + j] =
				(float)mission_cap_albedo(pos, b->sun[j]);
		stray_q_dcm(q, b->mib[j]);
	}
}

/* The block's albedo held from the epochs it was made at; the first
 * epoch after a gap makes its own (NAN in a gap: nothing is fed). */
static void hold_albedo(struct mission *m, const struct block *b, size_t i0,
			size_t nb)
{
	size_t every = albedo_every(m), i;

	for (i = i0; i < i0 + nb; i++) {
		const size_t j = i - i0;
		float pos[3] = { (float)b->r[j][0], (float)b->r[j][1],
				 (float)b->r[j][2] };

		if (b->bad[j])
			m->albedo[i] = NAN;
		else if (i % every == 0)
			continue;
		else if (i > 0 && isfinite(m->albedo[i - 1]))
			m->albedo[i] = m->albedo[i - 1];
		else
			m->albedo[i] = (float)mission_cap_albedo(pos, b->sun[j]);
	}
}

static void fly_head(struct mission *m, struct block *b, size_t h,
		     size_t i0, size_t nb, size_t sky_every)
{
	struct mission_head *hd = &m->head[h];
	size_t j;

	for (j = 0; j < nb; j++) {
		size_t i = i0 + j, s = i / sky_every;
		struct fdrfw_input in;
		struct fdrfw_output o;
		double mis[3][3];
		int k, l;

		if (b->bad[j]) {	/* in a gap: not flown */
			hd->mask[i] = MISSION_UNCOVERED;
			hd->after_gap = 1;
			continue;
		}
		/* the module's latches do not carry over time unseen (not
		 * fdrfw_init: the table's albedo is changed per frame, so
		 * its CRC no longer holds) */
		if (hd->after_gap)
			hd->ctx.latched = 0;
		hd->after_gap = 0;
		memset(&in, 0, sizeof(in));
		for (k = 0; k < 3; k++) {
			in.pos_km[k] = (float)b->r[j][k];
			for (l = 0; l < 3; l++)
				mis[k][l] = hd->m_bs[k][0] * b->mib[j][0][l] +
					    hd->m_bs[k][1] * b->mib[j][1][l] +
					    hd->m_bs[k][2] * b->mib[j][2][l];
		}
		mission_fw_q(mis, in.q);
		in.t_tt_s = b->t_tt[j];
		in.use_given_dirs = 1;
		memcpy(in.sun_dir, b->sun[j], sizeof(in.sun_dir));
		memcpy(in.moon_dir, b->moon[j], sizeof(in.moon_dir));
		in.t_exp_s = hd->table.t_exp_nominal_s;
		/* the ground feeds the regional albedo to the Earth term */
		hd->table.earth_albedo = m->albedo[i];
		(void)fdrfw_frame(&hd->ctx, &in, &o);
		hd->mask[i] = (uint8_t)(o.flags & STRAY_AVAIL_BLIND);
		hd->stars[i] = o.false_stars_total;
		b->flags[h][j] = o.flags;
		b->sun_deg[h][j] = o.theta_deg[FDRFW_SUN];
		if (i % sky_every == 0 && s < m->n_sky)
			sky_sample(hd, s, mis, b->r[j], b->sun[j], in.t_tt_s);
	}
}

/* The end of a row: any-head availability, the epoch in UTC (ISO 8601)
 * and each head's flag bits by name (flag_name), 0 or 1. */
static void csv_named(FILE *csv, const struct mission *m,
		      const struct block *b, size_t i0, size_t j, int any)
{
	char utc[64];
	size_t h;
	int k;

	stray_ccsds_format_epoch(m->t0 + (double)(i0 + j) * m->step_s,
				 STRAY_TS_UTC, utc, sizeof(utc));
	fprintf(csv, ",%d,%sZ", any, utc);
	for (h = 0; h < m->n_heads; h++)
		for (k = 0; k < 8; k++)
			fprintf(csv, ",%u", (unsigned)(b->flags[h][j] >> k) & 1u);
	fputc('\n', csv);
}

int mission_fly(const struct mission_args *a, struct mission *m,
		struct stray_error *err)
{
	struct stray_file_out out;
	FILE *csv = csv_open(a, m, &out, err);
	size_t i0, h, i, sky_every = (m->n + m->n_sky - 1) / m->n_sky;
	struct block *bb[2] = { malloc(sizeof(struct block)),
				malloc(sizeof(struct block)) };
	size_t nb0;
	int rc = STRAY_OK;
	long c;

	if ((a->csv && !csv) || !bb[0] || !bb[1]) {
		rc = bb[0] && bb[1] ? STRAY_EIO :
		     stray_error_set(err, STRAY_ENOMEM, "block", NULL);
		goto done;
	}
	m->n_sky = (m->n + sky_every - 1) / sky_every;
	nb0 = m->n < BLOCK ? m->n : BLOCK;
#pragma omp parallel for schedule(dynamic, 1)
	for (c = 0; c < (long)nb0; c += CHUNK)
		shared_chunk(m, bb[0], 0, (size_t)c, (size_t)c + CHUNK < nb0 ?
			     (size_t)c + CHUNK : nb0);
	for (i0 = 0; i0 < m->n; i0 += BLOCK) {
		struct block *b = bb[(i0 / BLOCK) & 1];
		struct block *next = bb[(i0 / BLOCK + 1) & 1];
		size_t nb = m->n - i0 < BLOCK ? m->n - i0 : BLOCK, j;
		size_t i1 = i0 + nb, nb1 = m->n - i1 < BLOCK ? m->n - i1 : BLOCK;

		hold_albedo(m, b, i0, nb);
#pragma omp parallel
#pragma omp single
		{
			long hh, cc;

			for (hh = 0; hh < (long)m->n_heads; hh++) {
#pragma omp task firstprivate(hh)
				fly_head(m, b, (size_t)hh, i0, nb, sky_every);
			}
			for (cc = 0; cc < (long)nb1; cc += CHUNK) {
#pragma omp task firstprivate(cc)
				shared_chunk(m, next, i1, (size_t)cc,
					     (size_t)cc + CHUNK < nb1 ?
					     (size_t)cc + CHUNK : nb1);
			}
		}
		for (j = 0; j < nb; j++) {
			uint8_t all = STRAY_AVAIL_BLIND;

			if (b->bad[j]) {	/* in a gap: neither up nor down */
				m->any_mask[i0 + j] = MISSION_UNCOVERED;
				continue;
			}
			for (h = 0; h < m->n_heads; h++)
				all &= m->head[h].mask[i0 + j] ? STRAY_AVAIL_BLIND : 0;
			m->any_mask[i0 + j] = all;
			if (!csv)
				continue;
			fprintf(csv, "%.3f,%.4f", (double)(i0 + j) * m->step_s,
				(double)m->albedo[i0 + j]);
			for (h = 0; h < m->n_heads; h++)
				fprintf(csv, ",%u,%.3f,%.4g", (unsigned)b->flags[h][j],
					(double)b->sun_deg[h][j],
					(double)m->head[h].stars[i0 + j]);
			csv_named(csv, m, b, i0, j, all == 0);
		}
	}
done:
	free(bb[0]);
	free(bb[1]);
	if (rc != STRAY_OK) {
		if (csv)
			stray_file_abort(&out);
		return rc;
	}
	for (h = 0; h < m->n_heads; h++) {
		struct mission_head *hd = &m->head[h];
		double sum = 0.0, mx = 0.0;

		stray_avail_summarise(hd->mask, m->n, m->step_s, &hd->st);
		for (i = 0; i < m->n; i++)
			if (!(hd->mask[i] & MISSION_UNCOVERED) &&
			    isfinite(hd->stars[i])) {
				sum += hd->stars[i];
				mx = fmax(mx, hd->stars[i]);
			}
		hd->stars_mean = hd->st.epochs ? sum / (double)hd->st.epochs : 0.0;
		hd->stars_max = mx;
	}
	stray_avail_summarise(m->any_mask, m->n, m->step_s, &m->any);
	return csv ? stray_file_commit(&out, err) : STRAY_OK;
}
