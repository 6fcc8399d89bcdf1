/*
 * oem.c - CCSDS OEM (502.0-B-3) KVN reader, interpolation and writer.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oem_cov.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/oem.h"

#define HERMITE_NODES_MAX 8

/* Physical bounds of an Earth-centred state (docs/limits.md): inside the
 * polar radius a point is under the surface at every latitude; 1e7 km is
 * far past the Earth's Hill sphere (1.5e6 km); 25 km/s is the escape
 * speed at the surface (11.2 km/s) with 22 km/s of hyperbolic excess. */
#define R_POLAR_KM 6356.752
#define R_MAX_KM 1e7
#define V_MAX_KM_S 25.0

enum { ST_HEADER, ST_META, ST_DATA, ST_COV };

struct oem_parse {
	const char *file;
	long line;
	struct stray_error *err;
	struct stray_oem *oem;
	size_t cap;
	int state, segments, seg_records;
	int have_frame, have_ts, have_center, have_interp;
	int first;		/* no line read yet */
	int frame;		/* this segment's (enum stray_ccsds_frame) */
	int ts;			/* this segment's time system */
	long cov_line;		/* the open COVARIANCE_START's line */
	struct oem_cov cov;
	struct stray_ccsds_frame_cache fc;	/* precession-nutation grid */
	/* epochs of the metadata, read at META_STOP (TIME_SYSTEM may come
	 * after them) */
	char when[4][48];
	long when_line[4];
};

static const char *const when_key[4] = { "START_TIME", "STOP_TIME",
	"USEABLE_START_TIME", "USEABLE_STOP_TIME" };

static int fail(struct oem_parse *p, const char *key, const char *why,
		const char *text)
{
	return stray_kvn_fail(p->err, p->file, p->line, key, why, text);
}

static int grow(struct oem_parse *p)
{
	struct stray_oem *o = p->oem;
	size_t cap = p->cap ? p->cap * 2 : 256;
	double *t = realloc(o->t, cap * sizeof(*o->t));
	double (*r)[3], (*v)[3];

	if (t)
		o->t = t;
	r = realloc(o->r, cap * sizeof(*o->r));
	if (r)
		o->r = r;
	v = realloc(o->v, cap * sizeof(*o->v));
	if (v)
		o->v = v;
	if (!t || !r || !v)
		return stray_error_set(p->err, STRAY_ENOMEM, "records", NULL);
	p->cap = cap;
	return STRAY_OK;
}

static void copy_name(char *dst, size_t size, const char *src)
{
	snprintf(dst, size, "%s", src);
}

static int meta_key(struct oem_parse *p, const char *k, const char *v)
{
	struct stray_oem *o = p->oem;
	int seg0 = p->segments == 1, i;

	for (i = 0; i < 4; i++)
		if (strcmp(k, when_key[i]) == 0) {
			copy_name(p->when[i], sizeof(p->when[i]), v);
			p->when_line[i] = p->line;
			return STRAY_OK;
		}
	if (strcmp(k, "OBJECT_NAME") == 0) {
		if (seg0)
			copy_name(o->object_name, sizeof(o->object_name), v);
	} else if (strcmp(k, "CENTER_NAME") == 0) {
		if (!stray_kvn_eq(v, "EARTH"))
			return fail(p, k, "only EARTH is supported", v);
		p->have_center = 1;
	} else if (strcmp(k, "REF_FRAME") == 0) {
		if ((p->frame = stray_ccsds_frame(v)) < 0)
			return fail(p, k, "not a supported frame (EME2000, ICRF, GCRF, ITRF..., GTOD, TOD, MOD, TEME)", v);
		if (seg0)
			copy_name(o->ref_frame, sizeof(o->ref_frame), v);
		copy_name(o->cover.seg[o->cover.n_seg - 1].frame_name,
			  sizeof(o->cover.seg[0].frame_name), v);
		o->cover.seg[o->cover.n_seg - 1].frame = p->frame;
		p->have_frame = 1;
	} else if (strcmp(k, "TIME_SYSTEM") == 0) {
		int ts = stray_ccsds_time_system(v);

		if (ts < 0)
			return fail(p, k, "not a supported time system (UTC, TAI, TT, GPS)", v);
		if (!seg0 && ts != o->time_system)
			return fail(p, k, "differs from the first segment's", v);
		o->time_system = p->ts = ts;
		o->cover.seg[o->cover.n_seg - 1].time_system = ts;
		p->have_ts = 1;
	} else if (strcmp(k, "INTERPOLATION") == 0) {
		int *in = &o->cover.seg[o->cover.n_seg - 1].interp;

		if (stray_kvn_eq(v, "LAGRANGE"))
			*in = STRAY_INTERP_LAGRANGE;
		else if (stray_kvn_eq(v, "HERMITE"))
			*in = STRAY_INTERP_HERMITE;
		else if (stray_kvn_eq(v, "LINEAR"))
			*in = STRAY_INTERP_LINEAR;
		else
			return fail(p, k, "not LAGRANGE, HERMITE or LINEAR", v);
		p->have_interp = 1;
	} else if (strcmp(k, "INTERPOLATION_DEGREE") == 0) {
		double d;

		if (!stray_kvn_number(v, &d) || d != floor(d) || d < 1 ||
		    d > STRAY_OEM_DEGREE_MAX)
			return fail(p, k, "not a whole degree in 1..15", v);
		o->cover.seg[o->cover.n_seg - 1].degree = (int)d;
	} else if (strcmp(k, "OBJECT_ID") != 0 &&
		   strcmp(k, "REF_FRAME_EPOCH") != 0) {
		return fail(p, k, "not an OEM metadata keyword", k);
	}
	return STRAY_OK;
}

static int meta_stop(struct oem_parse *p)
{
	struct stray_ccsds_seg *s = &p->oem->cover.seg[p->oem->cover.n_seg - 1];
	double t[4];
	int i, e;

	if (!p->have_center)
		return fail(p, "CENTER_NAME", "missing from the metadata", "");
	if (!p->have_frame)
		return fail(p, "REF_FRAME", "missing from the metadata", "");
	if (!p->have_ts)
		return fail(p, "TIME_SYSTEM", "missing from the metadata", "");
	for (i = 0; i < 4; i++) {
		if (!p->when[i][0])
			continue;
		if ((e = stray_ccsds_epoch(p->when[i], p->ts, &t[i])) != 0)
			return stray_kvn_fail(p->err, p->file, p->when_line[i],
					      when_key[i], e == -2 ?
					      "second 60 where no leap second is" :
					      "not a CCSDS epoch YYYY-MM-DDThh:mm:ss",
					      p->when[i]);
	}
	if ((s->have_u0 = p->when[2][0] != 0))
		s->u0 = t[2];
	if ((s->have_u1 = p->when[3][0] != 0))
		s->u1 = t[3];
	p->seg_records = 0;
	return STRAY_OK;
}

static int data_line(struct oem_parse *p, const struct stray_kvn_line *l)
{
	struct stray_oem *o = p->oem;
	double t, x[6], rn, vn;
	int k, e;

	if (l->n_field != 7 && l->n_field != 10)
		return fail(p, "data", "not an epoch and 6 (or 9) numbers",
			    l->field[0]);
	if ((e = stray_ccsds_epoch(l->field[0], o->time_system, &t)) != 0)
		return fail(p, "epoch", e == -2 ?
			    "second 60 where no leap second is" :
			    "not a CCSDS epoch YYYY-MM-DDThh:mm:ss", l->field[0]);
	for (k = 1; k < l->n_field; k++) {
		double a;

		if (!stray_kvn_number(l->field[k], k <= 6 ? &x[k - 1] : &a))
			return fail(p, "data", "not a number", l->field[k]);
	}
	/* in a segment epochs increase; segments may overlap (the later
	 * wins, stray/ccsds.h) */
	if (p->seg_records > 0 && !(t > o->t[o->n - 1]))
		return fail(p, "epoch", "not after the previous record's", l->field[0]);
	if (o->n == p->cap && grow(p) != STRAY_OK)
		return STRAY_ENOMEM;
	o->t[o->n] = t;
	/* an Earth-fixed or of-date state to inertial, once */
	stray_ccsds_to_inertial_cached(&p->fc, p->frame, t, x, x + 3);
	for (k = 0; k < 3; k++) {
		o->r[o->n][k] = x[k];
		o->v[o->n][k] = x[k + 3];
	}
	rn = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
	vn = sqrt(x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
	if (!(rn < R_MAX_KM))
		return fail(p, "data", "position beyond 1e7 km", l->field[1]);
	if (!(rn > R_POLAR_KM))
		return fail(p, "data", "position inside the Earth (|r| under 6356.752 km)",
			    l->field[1]);
	if (!(vn <= V_MAX_KM_S))
		return fail(p, "data", "velocity over 25 km/s: not an Earth orbit",
			    l->field[4]);
	o->n++;
	p->seg_records++;
	o->cover.seg[o->cover.n_seg - 1].n++;
	return STRAY_OK;
}

static int first_line(struct oem_parse *p, const struct stray_kvn_line *l)
{
	double ver;

	if (l->kind != STRAY_KVN_KEYVAL || strcmp(l->key, "CCSDS_OEM_VERS") != 0)
		return fail(p, "CCSDS_OEM_VERS", "must come first: not an OEM",
			    l->key ? l->key : l->field[0]);
	if (!stray_kvn_number(l->value, &ver) || ver < 1.0 || ver >= 4.0)
		return fail(p, "CCSDS_OEM_VERS", "not a version 1, 2 or 3", l->value);
	p->oem->version = ver;
	p->state = ST_HEADER;
	return STRAY_OK;
}

static int cov_unclosed(struct oem_parse *p)
{
	char at[48];

	snprintf(at, sizeof(at), "COVARIANCE_START at line %ld", p->cov_line);
	return fail(p, "COVARIANCE_STOP", "missing: the covariance block is not closed",
		    at);
}

static int one_line(void *ctx, const struct stray_kvn_line *l)
{
	struct oem_parse *p = ctx;

	if (p->first) {
		p->first = 0;
		return first_line(p, l);
	}
	if (p->state == ST_COV) {
		double t;

		if (l->kind == STRAY_KVN_WORD &&
		    strcmp(l->field[0], "COVARIANCE_STOP") == 0) {
			p->state = ST_DATA;
			p->oem->cover.seg[p->oem->cover.n_seg - 1].n_cov += p->cov.n;
			return oem_cov_stop(&p->cov, p->file, p->line, p->err);
		}
		/* a segment or an ephemeris line: the block was never closed,
		 * and reading on would take the rest of the file for it */
		if ((l->kind == STRAY_KVN_WORD &&
		     !stray_kvn_number(l->field[0], &t)) ||
		    (l->kind == STRAY_KVN_DATA &&
		     stray_ccsds_epoch(l->field[0], STRAY_TS_TT, &t) != -1))
			return cov_unclosed(p);
		return oem_cov_line(&p->cov, l, p->ts, p->file, p->line, p->err);
	}
	if (l->kind == STRAY_KVN_WORD) {
		const char *w = l->field[0];

		if (strcmp(w, "META_START") == 0 && p->state != ST_META) {
			struct stray_ccsds_seg *s;

			if (p->oem->cover.n_seg == STRAY_CCSDS_SEG_MAX)
				return fail(p, w, "more segments than 10000", w);
			if (!(s = stray_ccsds_cover_add(&p->oem->cover)))
				return stray_error_set(p->err, STRAY_ENOMEM, "segments", NULL);
			s->lo = p->oem->n;
			s->line = p->line;
			/* without INTERPOLATION: Hermite of degree 5 */
			s->interp = STRAY_INTERP_HERMITE;
			s->degree = 5;
			p->state = ST_META;
			p->segments++;
			p->have_frame = p->have_ts = p->have_center = 0;
			memset(p->when, 0, sizeof(p->when));
			return STRAY_OK;
		}
		if (strcmp(w, "META_STOP") == 0 && p->state == ST_META) {
			p->state = ST_DATA;
			return meta_stop(p);
		}
		if (strcmp(w, "COVARIANCE_START") == 0 && p->state == ST_DATA) {
			p->state = ST_COV;
			p->cov_line = p->line;
			memset(&p->cov, 0, sizeof(p->cov));
			return STRAY_OK;
		}
		return fail(p, w, "out of place", w);
	}
	if (l->kind == STRAY_KVN_KEYVAL) {
		if (p->state == ST_META)
			return meta_key(p, l->key, l->value);
		if (p->state == ST_HEADER && stray_kvn_header_key(l->key))
			return STRAY_OK;
		return fail(p, l->key, p->state == ST_DATA ?
			    "keyword inside the ephemeris data" :
			    "not an OEM header keyword", l->key);
	}
	if (p->state != ST_DATA)
		return fail(p, "data", "ephemeris line outside a segment (META_START .. META_STOP first)",
			    l->field[0]);
	return data_line(p, l);
}

void stray_oem_free(struct stray_oem *oem)
{
	free(oem->t);
	free(oem->r);
	free(oem->v);
	stray_ccsds_cover_free(&oem->cover);
	memset(oem, 0, sizeof(*oem));
}

/* Records a segment's interpolation takes around an epoch (each segment
 * is interpolated as its own metadata say). */
static size_t nodes(const struct stray_ccsds_seg *s)
{
	size_t m;

	if (s->interp == STRAY_INTERP_HERMITE) {
		m = ((size_t)s->degree + 2) / 2;
		return m < 2 ? 2 : m > HERMITE_NODES_MAX ? HERMITE_NODES_MAX : m;
	}
	return s->interp == STRAY_INTERP_LINEAR ? 2 : (size_t)s->degree + 1;
}

/* The segments' spans and gap rules once every record is in. */
static int oem_cover(struct oem_parse *p)
{
	struct stray_oem *o = p->oem;
	size_t i;
	int rc;

	for (i = 0; i < o->cover.n_seg; i++)
		o->cover.seg[i].nodes = nodes(&o->cover.seg[i]);
	rc = stray_ccsds_cover_finish(&o->cover, o->t, 2, p->file, p->err);
	if (rc != STRAY_OK)
		return rc;
	o->gap_s = o->cover.seg[0].gap_s;
	o->interp = o->cover.seg[0].interp;
	o->degree = o->cover.seg[0].degree;
	return STRAY_OK;
}

int stray_oem_parse(const char *buf, size_t len, const char *file,
		    struct stray_oem *oem, struct stray_error *err)
{
	struct oem_parse p;
	int rc;

	memset(oem, 0, sizeof(*oem));
	memset(&p, 0, sizeof(p));
	p.file = file;
	p.err = err;
	p.oem = oem;
	p.first = 1;
	oem->interp = STRAY_INTERP_HERMITE;
	oem->degree = 5;
	rc = stray_kvn_each(buf, len, file, &p.line, one_line, &p, err);
	if (rc == STRAY_OK && p.first)
		rc = fail(&p, "CCSDS_OEM_VERS", "missing: the file is empty", "");
	if (rc == STRAY_OK && p.state == ST_META)
		rc = fail(&p, "META_STOP", "missing at the end", "");
	if (rc == STRAY_OK && p.state == ST_COV)
		rc = cov_unclosed(&p);
	if (rc == STRAY_OK && oem->n < 2)
		rc = fail(&p, "data", "fewer than 2 ephemeris records", "");
	if (rc == STRAY_OK)
		rc = oem_cover(&p);
	if (rc != STRAY_OK)
		stray_oem_free(oem);
	return rc;
}

int stray_oem_read(const char *path, struct stray_oem *oem,
		   struct stray_error *err)
{
	char *buf;
	size_t len;
	int rc = stray_file_read(path, &buf, &len, err);

	if (rc != STRAY_OK)
		return rc;
	rc = stray_oem_parse(buf, len, path, oem, err);
	free(buf);
	return rc;
}

/* First of m records around t: t[k] <= t < t[k+1], centred, clamped. */
static size_t window(const double *ts, size_t n, double t, size_t m)
{
	size_t lo = 0, hi = n - 1, k;

	while (hi - lo > 1) {
		size_t mid = lo + (hi - lo) / 2;

		if (ts[mid] <= t)
			lo = mid;
		else
			hi = mid;
	}
	k = lo >= (m - 1) / 2 ? lo - (m - 1) / 2 : 0;
	if (k + m > n)
		k = n - m;
	return k;
}

/* Lagrange through (x_j, y_j), value at x (x relative to the nodes). */
static void lagrange(const double *x, size_t m, double at,
		     const double *y, size_t stride, size_t dim, double *out)
{
	size_t i, j, c;

	for (c = 0; c < dim; c++)
		out[c] = 0.0;
	for (j = 0; j < m; j++) {
		double lj = 1.0;

		for (i = 0; i < m; i++)
			if (i != j)
				lj *= (at - x[i]) / (x[j] - x[i]);
		for (c = 0; c < dim; c++)
			out[c] += lj * y[j * stride + c];
	}
}

/* Hermite through (x_j, y_j, y'_j) by Newton's divided differences on
 * doubled nodes; value and derivative at `at`. */
static void hermite(const double *x, size_t m, double at, const double *y,
		    const double *yd, double *p, double *dp)
{
	double z[2 * HERMITE_NODES_MAX] = { 0 }, q[2 * HERMITE_NODES_MAX] = { 0 };
	double c[2 * HERMITE_NODES_MAX] = { 0 };
	size_t n = 2 * m, i, j;

	for (i = 0; i < m; i++) {
		z[2 * i] = z[2 * i + 1] = x[i];
		q[2 * i] = q[2 * i + 1] = y[i];
	}
	c[0] = q[0];
	/* column j of the table in place, bottom up */
	for (j = 1; j < n; j++) {
		for (i = n - 1; i >= j; i--) {
			if (j == 1 && z[i] == z[i - 1])
				q[i] = yd[i / 2];
			else
				q[i] = (q[i] - q[i - 1]) / (z[i] - z[i - j]);
		}
		c[j] = q[j];
	}
	*p = c[n - 1];
	*dp = 0.0;
	for (j = n - 1; j-- > 0;) {
		*dp = *dp * (at - z[j]) + *p;
		*p = *p * (at - z[j]) + c[j];
	}
}

int stray_oem_state(const struct stray_oem *o, double t, double r[3],
		    double v[3])
{
	double x[STRAY_OEM_DEGREE_MAX + 1];
	long sg = stray_ccsds_cover_find(&o->cover, t);
	const struct stray_ccsds_seg *s;
	size_t m, k, j, lo, hi;
	int c;

	if (o->n < 2 || sg < 0)
		return STRAY_ERANGE;
	/* the owning segment's records only, as its metadata say */
	s = &o->cover.seg[sg];
	m = s->nodes;
	if (stray_ccsds_piece(o->t + s->lo, s->n, s->gap_s, t, m, &lo, &hi) != 0)
		return STRAY_ERANGE;
	lo += s->lo;
	hi += s->lo;
	if (lo == hi) {		/* a record alone between gaps, at its epoch */
		memcpy(r, o->r[lo], sizeof(o->r[lo]));
		memcpy(v, o->v[lo], sizeof(o->v[lo]));
		return STRAY_OK;
	}
	if (m > hi - lo + 1)
		m = hi - lo + 1;
	k = lo + window(o->t + lo, hi - lo + 1, t, m);
	for (j = 0; j < m; j++)
		x[j] = o->t[k + j] - o->t[k];
	if (s->interp != STRAY_INTERP_HERMITE) {
		lagrange(x, m, t - o->t[k], &o->r[k][0], 3, 3, r);
		lagrange(x, m, t - o->t[k], &o->v[k][0], 3, 3, v);
		return STRAY_OK;
	}
	for (c = 0; c < 3; c++) {
		double y[HERMITE_NODES_MAX], yd[HERMITE_NODES_MAX];

		for (j = 0; j < m; j++) {
			y[j] = o->r[k + j][c];
			yd[j] = o->v[k + j][c];
		}
		hermite(x, m, t - o->t[k], y, yd, &r[c], &v[c]);
	}
	return STRAY_OK;
}

int stray_oem_write(FILE *f, const char *object, int ts, const double *t,
		    const double (*r)[3], const double (*v)[3], size_t n,
		    int interp, int degree)
{
	static const char *const ts_names[] = { "UTC", "TAI", "TT", "GPS" };
	static const char *const in_names[] = { "LAGRANGE", "HERMITE", "LINEAR" };
	char e0[40], e1[40], e[40];
	size_t i;

	if (n < 2)
		return STRAY_EINVAL;
	stray_ccsds_format_epoch(t[0], ts, e0, sizeof(e0));
	stray_ccsds_format_epoch(t[n - 1], ts, e1, sizeof(e1));
	fprintf(f, "CCSDS_OEM_VERS = 2.0\nCREATION_DATE = %s\n"
		"ORIGINATOR = straylight\n\nMETA_START\nOBJECT_NAME = %s\n"
		"OBJECT_ID = %s\nCENTER_NAME = EARTH\nREF_FRAME = EME2000\n"
		"TIME_SYSTEM = %s\nSTART_TIME = %s\nSTOP_TIME = %s\n"
		"INTERPOLATION = %s\nINTERPOLATION_DEGREE = %d\nMETA_STOP\n\n",
		e0, object, object, ts_names[ts], e0, e1, in_names[interp],
		degree);
	for (i = 0; i < n; i++) {
		stray_ccsds_format_epoch(t[i], ts, e, sizeof(e));
		fprintf(f, "%s %.6f %.6f %.6f %.9f %.9f %.9f\n", e, r[i][0],
			r[i][1], r[i][2], v[i][0], v[i][1], v[i][2]);
	}
	return ferror(f) ? STRAY_EIO : STRAY_OK;
}
