/*
 * aem.c - CCSDS AEM (504.0-B-2) KVN reader of quaternion attitude, SLERP
 * and writer.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "aem_types.h"
#include "stray/aem.h"
#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define UNIT_TOL 1e-3

enum { ST_HEADER, ST_META, ST_BETWEEN, ST_DATA };
enum { FRAME_UNSET = -2, FRAME_BODY = -1 };	/* else enum stray_ccsds_frame */

struct aem_parse {
	const char *file;
	long line;
	struct stray_error *err;
	struct stray_aem *aem;
	size_t cap;
	int state, seg_records;
	int frame_a, frame_b;	/* FRAME_UNSET, FRAME_BODY or a frame */
	int dir;		/* -1 unset, 0 A2B, 1 B2A */
	int qtype;		/* -1 unset, 0 FIRST, 1 LAST */
	int type;		/* enum aem_type, -1 unset */
	int axis[3], have_seq;
	int have_ts, ts;
	int first;		/* no line read yet */
	int data_done;		/* this segment's DATA_STOP was read */
	struct stray_ccsds_frame_cache fc;	/* precession-nutation grid */
	/* USEABLE_START_TIME, USEABLE_STOP_TIME, START_TIME, STOP_TIME, read
	 * at META_STOP (TIME_SYSTEM may come after them) */
	char when[4][48];
	long when_line[4];
};

static const char *const when_key[4] = { "USEABLE_START_TIME",
	"USEABLE_STOP_TIME", "START_TIME", "STOP_TIME" };

static int fail(struct aem_parse *p, const char *key, const char *why,
		const char *text)
{
	return stray_kvn_fail(p->err, p->file, p->line, key, why, text);
}

static int grow(struct aem_parse *p)
{
	struct stray_aem *a = p->aem;
	size_t cap = p->cap ? p->cap * 2 : 256;
	double *t = realloc(a->t, cap * sizeof(*a->t));
	double (*q)[4];

	if (t)
		a->t = t;
	q = realloc(a->q, cap * sizeof(*a->q));
	if (q)
		a->q = q;
	if (!t || !q)
		return stray_error_set(p->err, STRAY_ENOMEM, "records", NULL);
	p->cap = cap;
	return STRAY_OK;
}

static struct stray_ccsds_seg *seg(struct aem_parse *p)
{
	return &p->aem->cover.seg[p->aem->cover.n_seg - 1];
}

/* A frame an attitude is given against: a celestial one (inertial,
 * Earth-fixed, of date), a body frame (anything else), or a frame that
 * moves with the orbit, which needs the orbit and is refused. */
static int ref_frame(struct aem_parse *p, const char *k, const char *v,
		     int *f)
{
	static const char *const lof[] = { "LVLH", "RTN", "RSW", "RIC",
		"QSW", "TNW", "NTW", "VNC", "VVLH", "LVLH_ROTATING",
		"LVLH_INERTIAL", "QSW_ROTATING", "QSW_INERTIAL", "NSW" };
	size_t i;

	for (i = 0; i < sizeof(lof) / sizeof(lof[0]); i++)
		if (stray_kvn_eq(v, lof[i]))
			return fail(p, k, "an orbit-relative frame: not supported (give the attitude against an inertial or Earth-fixed frame)", v);
	*f = stray_ccsds_frame(v);
	if (*f < 0)
		*f = FRAME_BODY;
	else
		snprintf(seg(p)->frame_name, sizeof(seg(p)->frame_name), "%s", v);
	return STRAY_OK;
}

/* Keywords 504.0-B-2 dropped from version 1 (direction is A to B and
 * q_c last), and the one it added. */
static int version_key(struct aem_parse *p, const char *k)
{
	int v2 = p->aem->version >= 2.0;

	if (v2 && (strcmp(k, "ATTITUDE_DIR") == 0 ||
		   strcmp(k, "QUATERNION_TYPE") == 0 ||
		   strcmp(k, "RATE_FRAME") == 0))
		return fail(p, k, "not an AEM 2.0 keyword (504.0-B-2: A to B, q_c last)", k);
	if (!v2 && strcmp(k, "ANGVEL_FRAME") == 0)
		return fail(p, k, "not an AEM 1.0 keyword", k);
	return STRAY_OK;
}

static int meta_key(struct aem_parse *p, const char *k, const char *v)
{
	struct stray_aem *a = p->aem;
	int i;

	if (version_key(p, k) != STRAY_OK)
		return STRAY_EPARSE;
	for (i = 0; i < 4; i++)
		if (strcmp(k, when_key[i]) == 0) {
			snprintf(p->when[i], sizeof(p->when[i]), "%s", v);
			p->when_line[i] = p->line;
			return STRAY_OK;
		}
	if (strcmp(k, "OBJECT_NAME") == 0) {
		if (a->cover.n_seg == 1)
			snprintf(a->object_name, sizeof(a->object_name), "%s", v);
	} else if (strcmp(k, "REF_FRAME_A") == 0) {
		return ref_frame(p, k, v, &p->frame_a);
	} else if (strcmp(k, "REF_FRAME_B") == 0) {
		return ref_frame(p, k, v, &p->frame_b);
	} else if (strcmp(k, "ATTITUDE_DIR") == 0) {
		if (stray_kvn_eq(v, "A2B"))
			p->dir = 0;
		else if (stray_kvn_eq(v, "B2A"))
			p->dir = 1;
		else
			return fail(p, k, "not A2B or B2A", v);
	} else if (strcmp(k, "TIME_SYSTEM") == 0) {
		int ts = stray_ccsds_time_system(v);

		if (ts < 0)
			return fail(p, k, "not a supported time system (UTC, TAI, TT, GPS)", v);
		if (a->cover.n_seg > 1 && ts != a->time_system)
			return fail(p, k, "differs from the first segment's", v);
		a->time_system = p->ts = seg(p)->time_system = ts;
		p->have_ts = 1;
	} else if (strcmp(k, "ATTITUDE_TYPE") == 0) {
		if ((p->type = aem_type(v)) < 0)
			return fail(p, k, "not an attitude type of 504.0 (QUATERNION[/DERIVATIVE|/RATE|/ANGVEL], EULER_ANGLE[/RATE|/DERIVATIVE|/ANGVEL], SPIN[/NUTATION|/NUTATION_MOM])", v);
		snprintf(seg(p)->kind, sizeof(seg(p)->kind), "%s", v);
	} else if (strcmp(k, "QUATERNION_TYPE") == 0) {
		if (stray_kvn_eq(v, "FIRST"))
			p->qtype = 0;
		else if (stray_kvn_eq(v, "LAST"))
			p->qtype = 1;
		else
			return fail(p, k, "not FIRST or LAST", v);
	} else if (strcmp(k, "EULER_ROT_SEQ") == 0) {
		if (aem_euler_seq(v, p->axis) != 0)
			return fail(p, k, "not one of the 12 rotation sequences (123, 321, ZXZ, ...)", v);
		p->have_seq = 1;
	} else if (strcmp(k, "OBJECT_ID") != 0 &&
		   strcmp(k, "CENTER_NAME") != 0 &&
		   strcmp(k, "INTERPOLATION_METHOD") != 0 &&
		   strcmp(k, "INTERPOLATION_DEGREE") != 0 &&
		   strcmp(k, "RATE_FRAME") != 0 &&
		   strcmp(k, "ANGVEL_FRAME") != 0) {
		return fail(p, k, "not an AEM metadata keyword", k);
	}
	return STRAY_OK;
}

static int meta_stop(struct aem_parse *p)
{
	struct stray_ccsds_seg *s = seg(p);
	int i, e;
	double t;

	if (p->frame_a == FRAME_UNSET)
		return fail(p, "REF_FRAME_A", "missing from the metadata", "");
	if (p->frame_b == FRAME_UNSET)
		return fail(p, "REF_FRAME_B", "missing from the metadata", "");
	if ((p->frame_a == FRAME_BODY) == (p->frame_b == FRAME_BODY))
		return fail(p, "REF_FRAME_A", p->frame_a != FRAME_BODY ?
			    "both frames celestial: which is the body?" :
			    "neither frame is inertial or Earth-fixed (EME2000, ICRF, GCRF, ITRF..., GTOD, TOD, MOD, TEME)", "");
	s->frame = p->frame_a != FRAME_BODY ? p->frame_a : p->frame_b;
	if (p->dir < 0 && p->aem->version < 2.0)
		return fail(p, "ATTITUDE_DIR", "missing from the metadata", "");
	if (!p->have_ts)
		return fail(p, "TIME_SYSTEM", "missing from the metadata", "");
	if (p->type < 0)
		return fail(p, "ATTITUDE_TYPE", "missing from the metadata", "");
	if (p->qtype < 0 && aem_type_is_quaternion(p->type) &&
	    p->aem->version < 2.0)
		return fail(p, "QUATERNION_TYPE", "missing from the metadata", "");
	if (!p->have_seq && aem_type_is_euler(p->type))
		return fail(p, "EULER_ROT_SEQ", "missing from the metadata", "");
	for (i = 0; i < 4; i++) {
		if (!p->when[i][0])
			continue;
		if ((e = stray_ccsds_epoch(p->when[i], p->ts, &t)) != 0)
			return stray_kvn_fail(p->err, p->file, p->when_line[i],
					      when_key[i], e == -2 ?
					      "second 60 where no leap second is" :
					      "not a CCSDS epoch YYYY-MM-DDThh:mm:ss",
					      p->when[i]);
		if (i == 0) {
			s->u0 = t;
			s->have_u0 = 1;
		} else if (i == 1) {
			s->u1 = t;
			s->have_u1 = 1;
		}
	}
	p->seg_records = 0;
	return STRAY_OK;
}

static void transpose(double m[3][3])
{
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < i; j++) {
			double x = m[i][j];

			m[i][j] = m[j][i];
			m[j][i] = x;
		}
}

/* q_ib from the data line's numbers: A -> B as the type says, the
 * direction, body on either side, then the external frame to inertial
 * at the epoch. */
static void to_q_ib(struct aem_parse *p, const double *x, double t,
		    double q[4], double *norm)
{
	double m[3][3], r[3][3], w[3], o[3][3];
	int i, j, k, ext = p->frame_a != FRAME_BODY ? p->frame_a : p->frame_b;

	aem_type_dcm(p->type, x, p->qtype == 0, p->axis, m, norm);
	if (p->dir == 1)	/* the data rotate B to A */
		transpose(m);
	if (p->frame_a == FRAME_BODY)	/* external is B: body -> external */
		transpose(m);
	stray_ccsds_frame_dcm_cached(&p->fc, ext, t, r, w);
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			for (o[i][j] = 0.0, k = 0; k < 3; k++)
				o[i][j] += m[i][k] * r[k][j];
	stray_dcm_q(o, q);
}

static int data_line(struct aem_parse *p, const struct stray_kvn_line *l)
{
	struct stray_aem *a = p->aem;
	double t, x[15], q[4], n;
	int k, e, nf = aem_type_fields(p->type);

	if (l->n_field != nf + 1) {
		char got[64];

		/* the reason must outlive this call: the counts go in the text */
		snprintf(got, sizeof(got), "%d numbers; %s takes %d",
			 l->n_field - 1, seg(p)->kind, nf);
		return fail(p, "data", "not an epoch and the attitude type's numbers", got);
	}
	if ((e = stray_ccsds_epoch(l->field[0], a->time_system, &t)) != 0)
		return fail(p, "epoch", e == -2 ?
			    "second 60 where no leap second is" :
			    "not a CCSDS epoch YYYY-MM-DDThh:mm:ss", l->field[0]);
	for (k = 0; k < nf; k++)
		if (!stray_kvn_number(l->field[k + 1], &x[k]))
			return fail(p, "data", "not a number", l->field[k + 1]);
	if ((p->type == AEM_SPIN || p->type == AEM_SPIN_NUTATION) &&
	    !(fabs(x[1]) <= 90.0))
		return fail(p, "data", "spin axis declination beyond 90 deg", l->field[2]);
	to_q_ib(p, x, t, q, &n);
	if (!(fabs(n - 1.0) <= UNIT_TOL))
		return fail(p, "data", "not a unit quaternion (|q| off 1 by more than 1e-3)",
			    l->field[1]);
	/* in a segment epochs increase; segments may overlap */
	if (p->seg_records > 0 && !(t > a->t[a->n - 1]))
		return fail(p, "epoch", "not after the previous record's", l->field[0]);
	if (a->n == p->cap && grow(p) != STRAY_OK)
		return STRAY_ENOMEM;
	/* the same rotation on the hemisphere of the previous record */
	if (a->n > 0 && q[0] * a->q[a->n - 1][0] + q[1] * a->q[a->n - 1][1] +
	    q[2] * a->q[a->n - 1][2] + q[3] * a->q[a->n - 1][3] < 0.0)
		for (k = 0; k < 4; k++)
			q[k] = -q[k];
	a->t[a->n] = t;
	memcpy(a->q[a->n], q, sizeof(q));
	a->n++;
	p->seg_records++;
	seg(p)->n++;
	return STRAY_OK;
}

static int word(struct aem_parse *p, const char *w)
{
	if (strcmp(w, "META_START") == 0 &&
	    (p->state == ST_HEADER || p->state == ST_BETWEEN)) {
		struct stray_ccsds_seg *s;

		if (p->state == ST_BETWEEN && !p->data_done)
			return fail(p, w, "the segment before has no DATA_START .. DATA_STOP", w);
		if (p->aem->cover.n_seg == STRAY_CCSDS_SEG_MAX)
			return fail(p, w, "more segments than 10000", w);
		if (!(s = stray_ccsds_cover_add(&p->aem->cover)))
			return stray_error_set(p->err, STRAY_ENOMEM, "segments", NULL);
		s->lo = p->aem->n;
		s->line = p->line;
		p->state = ST_META;
		p->frame_a = p->frame_b = FRAME_UNSET;
		p->dir = p->qtype = p->type = -1;
		p->have_ts = p->have_seq = p->data_done = 0;
		memset(p->when, 0, sizeof(p->when));
		return STRAY_OK;
	}
	if (strcmp(w, "META_STOP") == 0 && p->state == ST_META) {
		p->state = ST_BETWEEN;
		return meta_stop(p);
	}
	if (strcmp(w, "DATA_START") == 0 && p->state == ST_BETWEEN) {
		p->state = ST_DATA;
		return STRAY_OK;
	}
	if (strcmp(w, "DATA_STOP") == 0 && p->state == ST_DATA) {
		p->state = ST_BETWEEN;
		p->data_done = 1;
		return STRAY_OK;
	}
	return fail(p, w, "out of place", w);
}

static int one_line(void *ctx, const struct stray_kvn_line *l)
{
	struct aem_parse *p = ctx;
	double ver;

	if (p->first) {
		p->first = 0;
		if (l->kind != STRAY_KVN_KEYVAL ||
		    strcmp(l->key, "CCSDS_AEM_VERS") != 0)
			return fail(p, "CCSDS_AEM_VERS", "must come first: not an AEM",
				    l->key ? l->key : l->field[0]);
		if (!stray_kvn_number(l->value, &ver) || ver < 1.0 || ver >= 3.0)
			return fail(p, "CCSDS_AEM_VERS", "not a version 1 or 2", l->value);
		p->aem->version = ver;
		return STRAY_OK;
	}
	if (l->kind == STRAY_KVN_WORD)
		return word(p, l->field[0]);
	if (l->kind == STRAY_KVN_KEYVAL) {
		if (p->state == ST_META)
			return meta_key(p, l->key, l->value);
		if (p->state == ST_HEADER && stray_kvn_header_key(l->key))
			return STRAY_OK;
		return fail(p, l->key, p->state == ST_DATA ?
			    "keyword inside the attitude data" :
			    "not an AEM header keyword", l->key);
	}
	if (p->state != ST_DATA)
		return fail(p, "data", "attitude line outside DATA_START .. DATA_STOP",
			    l->field[0]);
	return data_line(p, l);
}

void stray_aem_free(struct stray_aem *aem)
{
	free(aem->t);
	free(aem->q);
	stray_ccsds_cover_free(&aem->cover);
	memset(aem, 0, sizeof(*aem));
}

/* The segments' spans and gap rules once every record is in: SLERP's
 * window is the two records around an epoch. */
static int aem_cover(struct aem_parse *p)
{
	struct stray_aem *a = p->aem;
	int rc = stray_ccsds_cover_finish(&a->cover, a->t, 2, p->file, p->err);

	if (rc == STRAY_OK)
		a->gap_s = a->cover.seg[0].gap_s;
	return rc;
}

int stray_aem_parse(const char *buf, size_t len, const char *file,
		    struct stray_aem *aem, struct stray_error *err)
{
	struct aem_parse p;
	int rc;

	memset(aem, 0, sizeof(*aem));
	memset(&p, 0, sizeof(p));
	p.file = file;
	p.err = err;
	p.aem = aem;
	p.first = 1;
	rc = stray_kvn_each(buf, len, file, &p.line, one_line, &p, err);
	if (rc == STRAY_OK && p.first)
		rc = fail(&p, "CCSDS_AEM_VERS", "missing: the file is empty", "");
	if (rc == STRAY_OK && p.state == ST_DATA)
		rc = fail(&p, "DATA_STOP", "missing at the end", "");
	if (rc == STRAY_OK && p.state == ST_META)
		rc = fail(&p, "META_STOP", "missing at the end", "");
	if (rc == STRAY_OK && aem->n < 2)
		rc = fail(&p, "data", "fewer than 2 attitude records", "");
	if (rc == STRAY_OK)
		rc = aem_cover(&p);
	if (rc != STRAY_OK)
		stray_aem_free(aem);
	return rc;
}

int stray_aem_read(const char *path, struct stray_aem *aem,
		   struct stray_error *err)
{
	char *buf;
	size_t len;
	int rc = stray_file_read(path, &buf, &len, err);

	if (rc != STRAY_OK)
		return rc;
	rc = stray_aem_parse(buf, len, path, aem, err);
	free(buf);
	return rc;
}

int stray_aem_attitude(const struct stray_aem *a, double t, double q[4])
{
	long sg = stray_ccsds_cover_find(&a->cover, t);
	const struct stray_ccsds_seg *s;
	size_t lo, hi;

	if (a->n < 2 || sg < 0)
		return STRAY_ERANGE;
	/* the owning segment's records only */
	s = &a->cover.seg[sg];
	if (stray_ccsds_piece(a->t + s->lo, s->n, s->gap_s, t, 0, &lo, &hi) != 0)
		return STRAY_ERANGE;
	lo += s->lo;
	hi += s->lo;
	if (lo == hi) {		/* on a record at a gap's edge */
		memcpy(q, a->q[lo], sizeof(a->q[lo]));
		return STRAY_OK;
	}
	stray_q_slerp(a->q[lo], a->q[hi],
		      (t - a->t[lo]) / (a->t[hi] - a->t[lo]), q);
	return STRAY_OK;
}

int stray_aem_write(FILE *f, const char *object, int ts, const double *t,
		    const double (*q)[4], size_t n)
{
	static const char *const ts_names[] = { "UTC", "TAI", "TT", "GPS" };
	char e0[40], e1[40], e[40];
	size_t i;

	if (n < 2)
		return STRAY_EINVAL;
	stray_ccsds_format_epoch(t[0], ts, e0, sizeof(e0));
	stray_ccsds_format_epoch(t[n - 1], ts, e1, sizeof(e1));
	fprintf(f, "CCSDS_AEM_VERS = 1.0\nCREATION_DATE = %s\n"
		"ORIGINATOR = straylight\n\nMETA_START\nOBJECT_NAME = %s\n"
		"OBJECT_ID = %s\nREF_FRAME_A = EME2000\nREF_FRAME_B = SC_BODY_1\n"
		"ATTITUDE_DIR = A2B\nTIME_SYSTEM = %s\nSTART_TIME = %s\n"
		"STOP_TIME = %s\nATTITUDE_TYPE = QUATERNION\n"
		"QUATERNION_TYPE = LAST\nINTERPOLATION_METHOD = LINEAR\n"
		"INTERPOLATION_DEGREE = 1\nMETA_STOP\n\nDATA_START\n",
		e0, object, object, ts_names[ts], e0, e1);
	for (i = 0; i < n; i++) {
		stray_ccsds_format_epoch(t[i], ts, e, sizeof(e));
		fprintf(f, "%s %.12f %.12f %.12f %.12f\n", e, q[i][1], q[i][2],
			q[i][3], q[i][0]);
	}
	fputs("DATA_STOP\n", f);
	return ferror(f) ? STRAY_EIO : STRAY_OK;
}
