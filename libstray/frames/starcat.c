/*
 * starcat.c - the parsers of stray/starcat.h: the I/311 and BSC5 fixed
 * columns, the I/239 `|` fields, the CSV by its header; and the
 * catalogue they fill, freed.  Columns are
 * the catalogues' ReadMe byte ranges (1-based, inclusive).
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/errfmt.h"
#include "stray/sizes.h"
#include "stray/starcat.h"

#define PI 3.14159265358979323846
#define LINE_MAX_CH 4096
#define CSV_COLS 9

/* V from Hipparcos Hp and B-V (the fit of stray/starcat.h). */
double stray_hp_to_v(double hp, double b_v)
{
	double c = fmax(-0.2, fmin(1.8, b_v));

	return hp - 0.2964 * c + 0.1110 * c * c;
}

void stray_starcat_free(struct stray_starcat *c)
{
	free(c->s);
	memset(c, 0, sizeof(*c));
}

/* A field's text: blank (1), a number (0, *v), or not a number (-1). */
static int num(const char *p, size_t n, double *v)
{
	char buf[64], *end;
	size_t i = 0, j;

	while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r'))
		i++;
	j = n;
	while (j > i && (p[j - 1] == ' ' || p[j - 1] == '\t' || p[j - 1] == '\r'))
		j--;
	if (i == j)
		return 1;
	if (j - i >= sizeof(buf))
		return -1;
	memcpy(buf, p + i, j - i);
	buf[j - i] = '\0';
	*v = strtod(buf, &end);
	return *end || !isfinite(*v) ? -1 : 0;
}

/* Columns a..b (1-based) of a line of length n: as num(); past the end
 * of the line counts as blank. */
static int col(const char *l, size_t n, int a, int b, double *v)
{
	if ((size_t)a > n)
		return 1;
	return num(l + a - 1, ((size_t)b > n ? n : (size_t)b) - (size_t)a + 1, v);
}

struct ctx {
	const char *name;
	long line;
	struct stray_error *err;
	struct stray_starcat *c;
	size_t cap;
};

static int bad(struct ctx *x, const char *field, const char *why)
{
	return stray_error_at(x->err, STRAY_EPARSE, x->name, x->line, field, why);
}

/* A catalogue number: a whole number in [0, 1e9) (fuzzing found a
 * 1e26 cast to long, undefined behaviour). */
static int ident(struct ctx *x, double v, long *id)
{
	if (!(v >= 0.0 && v < 1e9) || v != floor(v))
		return bad(x, "id", "not a whole number in [0, 1e9)");
	*id = (long)v;
	return STRAY_OK;
}

static int push(struct ctx *x, const struct stray_starcat_star *s)
{
	if (!(s->dec_deg >= -90.0 && s->dec_deg <= 90.0))
		return bad(x, "dec", "outside [-90, 90] deg");
	if (!(s->ra_deg >= -360.0 && s->ra_deg <= 720.0))
		return bad(x, "ra", "outside [-360, 720] deg");
	if (!(fabs(s->pmra_mas_yr) <= STRAY_STARCAT_PM_MAX_MAS_YR) ||
	    !(fabs(s->pmdec_mas_yr) <= STRAY_STARCAT_PM_MAX_MAS_YR))
		return bad(x, "proper motion", "over 20000 mas/yr (docs/limits.md)");
	if (!(s->v_mag > -30.0 && s->v_mag < 40.0))
		return bad(x, "magnitude", "outside (-30, 40)");
	if (!(s->b_v > -5.0 && s->b_v < 10.0))
		return bad(x, "B-V", "outside (-5, 10)");
	if (!(s->epoch_jyear > 1000.0 && s->epoch_jyear < 3000.0))
		return bad(x, "epoch_jyear", "outside (1000, 3000)");
	if (x->c->n == x->cap) {
		size_t cap = x->cap ? 2 * x->cap : 1024;
		struct stray_starcat_star *p;

		if (x->c->n >= STRAY_STARCAT_MAX_STARS)
			return bad(x, "stars", "more than 2000000 (docs/limits.md)");
		p = realloc(x->c->s, cap * sizeof(*p));
		if (!p)
			return stray_error_set(x->err, STRAY_ENOMEM, "catalogue",
					       "out of memory");
		x->c->s = p;
		x->cap = cap;
	}
	x->c->s[x->c->n++] = *s;
	return STRAY_OK;
}

/* I/311 hip2.dat: HIP 1-6, RArad 16-28, DErad 30-42 (rad, J1991.25),
 * pmRA 52-59, pmDE 61-68 (mas/yr), Hpmag 130-136, B-V 153-158. */
static int hip2_line(struct ctx *x, const char *l, size_t n)
{
	struct stray_starcat_star s = { 0 };
	double hip = 0, ra, de, hp;
	int r;

	if ((r = col(l, n, 1, 6, &hip)) < 0)
		return bad(x, "HIP", "not a number");
	if ((r = col(l, n, 16, 28, &ra)) || (r = col(l, n, 30, 42, &de)))
		return r < 0 ? bad(x, "RArad/DErad", "not a number") :
			(x->c->n_skipped++, STRAY_OK);
	/* a blank proper motion stays 0 (s is zeroed) */
	if (col(l, n, 52, 59, &s.pmra_mas_yr) < 0 ||
	    col(l, n, 61, 68, &s.pmdec_mas_yr) < 0)
		return bad(x, "pmRA/pmDE", "not a number");
	if ((r = col(l, n, 130, 136, &hp)) || (r = col(l, n, 153, 158, &s.b_v)))
		return r < 0 ? bad(x, "Hpmag/B-V", "not a number") :
			(x->c->n_skipped++, STRAY_OK);
	s.ra_deg = ra * 180.0 / PI;
	s.dec_deg = de * 180.0 / PI;
	s.epoch_jyear = 1991.25;
	s.v_mag = stray_hp_to_v(hp, s.b_v);
	return ident(x, hip, &s.id) ? STRAY_EPARSE : push(x, &s);
}

/* The k-th (0-based) `|` field of an I/239 record, or NULL. */
static const char *pipe_field(const char *l, size_t n, int k, size_t *len)
{
	size_t i = 0, start = 0;
	int f = 0;

	for (i = 0; i <= n; i++)
		if (i == n || l[i] == '|') {
			if (f == k) {
				*len = i - start;
				return l + start;
			}
			f++;
			start = i + 1;
		}
	return NULL;
}

/* I/239 hip_main.dat: fields H1 HIP, H5 Vmag, H8 RAdeg, H9 DEdeg
 * (J1991.25), H12 pmRA, H13 pmDE, H37 B-V. */
static int hip1_line(struct ctx *x, const char *l, size_t n)
{
	static const int k[6] = { 1, 5, 8, 9, 37, 12 };
	static const char *names[6] = { "HIP", "Vmag", "RAdeg", "DEdeg", "B-V",
					"pmRA" };
	struct stray_starcat_star s = { 0 };
	double v[7] = { 0 };
	size_t len;
	const char *p;
	int i, r;

	for (i = 0; i < 7; i++) {
		int kk = i < 6 ? k[i] : 13;

		if (!(p = pipe_field(l, n, kk, &len)))
			return bad(x, "record", "fewer than 38 `|` fields");
		r = num(p, len, &v[i]);
		if (r < 0)
			return bad(x, i < 6 ? names[i] : "pmDE", "not a number");
		if (r == 1 && i >= 1 && i <= 4)
			return x->c->n_skipped++, STRAY_OK;
		if (r == 1)
			v[i] = 0.0;
	}
	if (ident(x, v[0], &s.id))
		return STRAY_EPARSE;
	s.v_mag = v[1];
	s.ra_deg = v[2];
	s.dec_deg = v[3];
	s.b_v = v[4];
	s.pmra_mas_yr = v[5];
	s.pmdec_mas_yr = v[6];
	s.epoch_jyear = 1991.25;
	return push(x, &s);
}

/* BSC5 (V/50 catalog): HR 1-4, RA J2000 76-77 h 78-79 m 80-83 s, Dec
 * 84 sign 85-86 d 87-88 m 89-90 s, Vmag 103-107, B-V 110-114, pmRA
 * 149-154 and pmDE 155-160 (arcsec/yr, J2000). */
static int bsc5_line(struct ctx *x, const char *l, size_t n)
{
	struct stray_starcat_star s = { 0 };
	double hr = 0, h, m, sec, d, dm, ds, pa = 0, pd = 0;
	int r;

	if (col(l, n, 1, 4, &hr) < 0)
		return bad(x, "HR", "not a number");
	if ((r = col(l, n, 76, 77, &h)) || (r = col(l, n, 78, 79, &m)) ||
	    (r = col(l, n, 80, 83, &sec)) || (r = col(l, n, 85, 86, &d)) ||
	    (r = col(l, n, 87, 88, &dm)) || (r = col(l, n, 89, 90, &ds)))
		return r < 0 ? bad(x, "RA/Dec J2000", "not a number") :
			(x->c->n_skipped++, STRAY_OK);
	if (n < 84 || (l[83] != '+' && l[83] != '-'))
		return bad(x, "DE-", "not + or -");
	if ((r = col(l, n, 103, 107, &s.v_mag)) || (r = col(l, n, 110, 114, &s.b_v)))
		return r < 0 ? bad(x, "Vmag/B-V", "not a number") :
			(x->c->n_skipped++, STRAY_OK);
	if (col(l, n, 149, 154, &pa) < 0 || col(l, n, 155, 160, &pd) < 0)
		return bad(x, "pmRA/pmDE", "not a number");
	if (h >= 24 || m >= 60 || sec >= 60 || dm >= 60 || ds >= 60 || h < 0 ||
	    m < 0 || sec < 0 || d < 0 || dm < 0 || ds < 0)
		return bad(x, "RA/Dec J2000", "h/d, m, s out of range");
	s.ra_deg = 15.0 * (h + m / 60.0 + sec / 3600.0);
	s.dec_deg = (l[83] == '-' ? -1.0 : 1.0) * (d + dm / 60.0 + ds / 3600.0);
	s.pmra_mas_yr = pa * 1000.0;
	s.pmdec_mas_yr = pd * 1000.0;
	s.epoch_jyear = 2000.0;
	return ident(x, hr, &s.id) ? STRAY_EPARSE : push(x, &s);
}

/* CSV columns by name; -1 when absent. */
struct csv_map {
	int at[CSV_COLS];
};

static const char *const csv_names[CSV_COLS] = {
	"ra_deg", "dec_deg", "v_mag", "b_v", "hip", "pmra_mas_yr",
	"pmdec_mas_yr", "epoch_jyear", "hp_mag"
};

static int csv_header(struct ctx *x, const char *l, size_t n, struct csv_map *m)
{
	size_t i = 0, start = 0;
	int k, c = 0;

	for (k = 0; k < CSV_COLS; k++)
		m->at[k] = -1;
	for (i = 0; i <= n; i++) {
		if (i < n && l[i] != ',')
			continue;
		for (k = 0; k < CSV_COLS; k++) {
			size_t w = strlen(csv_names[k]), a = start, b = i;

			while (a < b && l[a] == ' ')
				a++;
			while (b > a && (l[b - 1] == ' ' || l[b - 1] == '\r'))
				b--;
			if (b - a == w && memcmp(l + a, csv_names[k], w) == 0) {
				if (m->at[k] >= 0)
					return bad(x, csv_names[k], "column named twice");
				m->at[k] = c;
			}
		}
		c++;
		start = i + 1;
	}
	for (k = 0; k < 4; k++)
		if (m->at[k] < 0)
			return bad(x, csv_names[k], "required column missing");
	return STRAY_OK;
}

static int csv_line(struct ctx *x, const char *l, size_t n,
		    const struct csv_map *m)
{
	struct stray_starcat_star s = { 0 };
	double v[CSV_COLS];
	int k, blank[CSV_COLS];

	for (k = 0; k < CSV_COLS; k++) {
		size_t len, i = 0, start = 0;
		const char *p = NULL;
		int c = 0;

		blank[k] = 1;
		v[k] = 0.0;
		if (m->at[k] < 0)
			continue;
		for (i = 0; i <= n && !p; i++)
			if (i == n || l[i] == ',') {
				if (c++ == m->at[k]) {
					p = l + start;
					len = i - start;
				}
				start = i + 1;
			}
		if (!p)
			return bad(x, csv_names[k], "missing (short row)");
		if ((blank[k] = num(p, len, &v[k])) < 0)
			return bad(x, csv_names[k], "not a number");
	}
	if (blank[0] || blank[1] || blank[3] || (blank[2] && blank[8]))
		return bad(x, blank[0] ? "ra_deg" : blank[1] ? "dec_deg" :
			   blank[3] ? "b_v" : "v_mag", "empty (v_mag may be empty when hp_mag is given)");
	s.ra_deg = v[0];
	s.dec_deg = v[1];
	s.b_v = v[3];
	s.v_mag = blank[2] ? stray_hp_to_v(v[8], v[3]) : v[2];
	if (ident(x, v[4], &s.id))
		return STRAY_EPARSE;
	s.pmra_mas_yr = v[5];
	s.pmdec_mas_yr = v[6];
	s.epoch_jyear = blank[7] ? 2000.0 : v[7];
	return push(x, &s);
}

/* The kind from the first data line. */
static int kind_of(const char *l, size_t n)
{
	double a, b;

	if (memchr(l, '|', n))
		return STRAY_STARCAT_HIP1;
	if (n >= 3 && (memcmp(l, "ra_", 3) == 0 || memchr(l, ',', n)))
		return STRAY_STARCAT_CSV;
	if (n >= 158 && col(l, n, 16, 28, &a) == 0 && col(l, n, 30, 42, &b) == 0 &&
	    l[14] == ' ' && l[28] == ' ')
		return STRAY_STARCAT_HIP2;
	if (n >= 114 && n <= 200)
		return STRAY_STARCAT_BSC5;
	return 0;
}

int stray_starcat_parse(const char *text, size_t len, const char *name,
			struct stray_starcat *c, struct stray_error *err)
{
	struct ctx x = { name, 0, err, c, 0 };
	struct csv_map map;
	size_t i = 0;
	int rc = STRAY_OK;

	memset(c, 0, sizeof(*c));
	if (stray_size_check(len, 1, STRAY_STARCAT_MAX_BYTES, SIZE_MAX, name,
			     "file size", NULL, err))
		return STRAY_EINVAL;
	while (i < len && rc == STRAY_OK) {
		const char *l = text + i, *e = memchr(l, '\n', len - i);
		size_t n = e ? (size_t)(e - l) : len - i;

		i += n + 1;
		x.line++;
		if (n > 0 && l[n - 1] == '\r')
			n--;
		if (n == 0 || l[0] == '#')
			continue;
		if (memchr(l, '\0', n))
			rc = bad(&x, "line", "holds a NUL byte");
		else if (n > LINE_MAX_CH)
			rc = bad(&x, "line", "longer than 4096 characters");
		else if (!c->kind) {
			if (!(c->kind = kind_of(l, n)))
				rc = bad(&x, "catalogue", "not hip2.dat, hip_main.dat, BSC5 or a CSV with ra_deg,dec_deg,v_mag,b_v");
			else if (c->kind == STRAY_STARCAT_CSV)
				rc = csv_header(&x, l, n, &map);
			else
				i = (size_t)(l - text), x.line--;	/* again, as data */
		} else if (c->kind == STRAY_STARCAT_HIP2)
			rc = hip2_line(&x, l, n);
		else if (c->kind == STRAY_STARCAT_HIP1)
			rc = hip1_line(&x, l, n);
		else if (c->kind == STRAY_STARCAT_BSC5)
			rc = bsc5_line(&x, l, n);
		else
			rc = csv_line(&x, l, n, &map);
	}
	if (rc == STRAY_OK && c->n == 0)
		rc = stray_error_at(err, STRAY_EINVAL, name, 0, "stars",
				    "the catalogue holds no usable star");
	if (rc != STRAY_OK)
		stray_starcat_free(c);
	return rc;
}
