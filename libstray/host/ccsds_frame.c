/*
 * ccsds_frame.c - Earth-fixed and true-of-date frames of an OEM or AEM
 * to the inertial frame, with ERFA: missions deliver GNSS ephemerides in
 * ITRF, TLE-propagated ones in TEME, attitude against GTOD.  IAU 2000B
 * precession-nutation (1 mas of 2000A: 3 cm at LEO) keeps a year of
 * records at 10 s affordable; UT1 - UTC and the pole from an IERS table
 * when one is loaded, zero otherwise (the error that implies is in
 * docs/availability.md).
 */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <erfa.h>

#include "stray/ccsds.h"
#include "stray/errfmt.h"
#include "stray/file.h"

#define J2000_JD 2451545.0
#define TT_MINUS_TAI 32.184
#define OMEGA_EARTH 7.292115146706979e-5	/* rad/s, IERS nominal */
#define AS2R 4.848136811095359935899141e-6	/* rad per arcsec */

static struct { size_t n; double *mjd, *xp, *yp, *dut1; } eop;

int stray_ccsds_frame(const char *text)
{
	const char *d;

	if (stray_ccsds_inertial_frame(text))
		return STRAY_FRAME_INERTIAL;
	if (stray_kvn_eq(text, "GTOD") || stray_kvn_eq(text, "TDR"))
		return STRAY_FRAME_GTOD;
	if (stray_kvn_eq(text, "TOD"))
		return STRAY_FRAME_TOD;
	if (stray_kvn_eq(text, "MOD"))
		return STRAY_FRAME_MOD;
	if (stray_kvn_eq(text, "TEME"))
		return STRAY_FRAME_TEME;
	/* ITRF, ITRF2014, ITRF-93, ITRF_97: a realisation of the ITRS */
	if (strlen(text) < 4 || !stray_kvn_eq((char[5]){ text[0], text[1],
				text[2], text[3], '\0' }, "ITRF"))
		return -1;
	d = text + 4;
	if (*d == '-' || *d == '_')
		d++;
	else if (*d == '\0')
		return STRAY_FRAME_ITRF;
	if (!*d)
		return -1;
	for (; *d; d++)
		if (!isdigit((unsigned char)*d))
			return -1;
	return STRAY_FRAME_ITRF;
}

/* The frame rotation about z by a (maps coordinates to the turned axes). */
static void rot_z(double a, double m[3][3])
{
	double r[3][3] = { { cos(a), sin(a), 0 }, { -sin(a), cos(a), 0 },
			   { 0, 0, 1 } }, o[3][3];
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			for (o[i][j] = 0.0, k = 0; k < 3; k++)
				o[i][j] += r[i][k] * m[k][j];
	memcpy(m, o, sizeof(o));
}

int stray_ccsds_eop_at(double mjd, double *xp, double *yp, double *dut1)
{
	size_t lo = 0, hi = eop.n - 1;
	double f;

	*xp = *yp = *dut1 = 0.0;
	if (eop.n < 2 || !(mjd >= eop.mjd[0] && mjd <= eop.mjd[eop.n - 1]))
		return 0;
	while (hi - lo > 1) {
		size_t mid = lo + (hi - lo) / 2;

		if (eop.mjd[mid] <= mjd)
			lo = mid;
		else
			hi = mid;
	}
	f = (mjd - eop.mjd[lo]) / (eop.mjd[hi] - eop.mjd[lo]);
	*xp = (eop.xp[lo] + f * (eop.xp[hi] - eop.xp[lo])) * AS2R;
	*yp = (eop.yp[lo] + f * (eop.yp[hi] - eop.yp[lo])) * AS2R;
	/* a leap second between the two days steps UT1 - UTC by 1 s */
	if (fabs(eop.dut1[hi] - eop.dut1[lo]) > 0.5)
		*dut1 = f < 1.0 ? eop.dut1[lo] : eop.dut1[hi];
	else
		*dut1 = eop.dut1[lo] + f * (eop.dut1[hi] - eop.dut1[lo]);
	return 1;
}

/* The slowly turning parts on a grid: precession-nutation (IAU 2000B at
 * TT) and the equation of the equinoxes (at UT1), linear between nodes
 * NODE_S apart.  2000B's fastest term of any size (13.66 d, 0.23") bends
 * by A (w h)^2 / 8 = 0.3 microarcsec over 600 s: nothing, and a record
 * then costs a polynomial for GMST instead of 77 nutation terms. */
#define NODE_S 600.0

static void npb_at(double x, double *out)
{
	eraPnm00b(J2000_JD, x / 86400.0, (double (*)[3])out);
}

static void ee_at(double x, double *out)
{
	*out = eraEe00b(J2000_JD, x / 86400.0);
}

static void slot_at(struct stray_ccsds_frame_slot *s, double x, int n,
		    void (*f)(double, double *), double *out)
{
	double node = floor(x / NODE_S) * NODE_S, g;
	int k;

	if (!s->have || s->node != node) {
		if (s->have && s->node + NODE_S == node)	/* moving on */
			memcpy(s->v[0], s->v[1], sizeof(s->v[0]));
		else
			f(node, s->v[0]);
		f(node + NODE_S, s->v[1]);
		s->node = node;
		s->have = 1;
	}
	g = (x - node) / NODE_S;
	for (k = 0; k < n; k++)
		out[k] = s->v[0][k] + g * (s->v[1][k] - s->v[0][k]);
}

void stray_ccsds_frame_dcm_cached(struct stray_ccsds_frame_cache *c,
				  int frame, double t_tt, double m[3][3],
				  double w[3])
{
	double tt2 = t_tt / 86400.0, tai2 = tt2 - TT_MINUS_TAI / 86400.0;
	double u1, u2, xp, yp, dut1, ut2, ee, gst, pom[3][3];
	int i;

	for (i = 0; i < 3; i++) {
		w[i] = 0.0;
		memset(m[i], 0, sizeof(m[i]));
		m[i][i] = 1.0;
	}
	if (frame == STRAY_FRAME_INERTIAL)
		return;
	if (frame == STRAY_FRAME_MOD) {
		eraPmat00(J2000_JD, tt2, m);
		return;
	}
	if (c)
		slot_at(&c->npb, t_tt, 9, npb_at, &m[0][0]);
	else
		eraPnm00b(J2000_JD, tt2, m);
	if (frame == STRAY_FRAME_TOD)
		return;
	/* UT1 for the Earth's rotation: UTC from TAI, then the table's
	 * UT1 - UTC (zero without one) */
	/* ERFA's status 1 is a "dubious year", past its release's leap
	 * table by 5 years (2028 for ERFA 2.0): its values still hold */
	if (eraTaiutc(J2000_JD, tai2, &u1, &u2) < 0) {
		u1 = J2000_JD;
		u2 = tai2;
	}
	stray_ccsds_eop_at(u1 - 2400000.5 + u2, &xp, &yp, &dut1);
	ut2 = u2 + dut1 / 86400.0;
	/* the equation of the equinoxes at UT1, as eraGst00b takes it */
	if (c)
		slot_at(&c->ee, (u1 - J2000_JD + ut2) * 86400.0, 1, ee_at, &ee);
	else
		ee = eraEe00b(u1, ut2);
	if (frame == STRAY_FRAME_TEME) {
		/* mean equinox on the true equator: EqE from the true one */
		rot_z(ee, m);
		return;
	}
	gst = eraAnp(eraGmst00(u1, ut2, u1, ut2) + ee);
	if (frame == STRAY_FRAME_GTOD) {
		rot_z(gst, m);
	} else {
		/* eraC2t00b's product, the nutation from the grid */
		eraPom00(xp, yp, eraSp00(J2000_JD, tt2), pom);
		eraC2teqx(m, gst, pom, m);
	}
	w[2] = OMEGA_EARTH;
}

void stray_ccsds_frame_dcm(int frame, double t_tt, double m[3][3],
			   double w[3])
{
	stray_ccsds_frame_dcm_cached(NULL, frame, t_tt, m, w);
}

void stray_ccsds_to_inertial_cached(struct stray_ccsds_frame_cache *c,
				    int frame, double t_tt, double r[3],
				    double v[3])
{
	double m[3][3], w[3], ri[3], vf[3];
	int i, j;

	if (frame == STRAY_FRAME_INERTIAL)
		return;
	stray_ccsds_frame_dcm_cached(c, frame, t_tt, m, w);
	/* the frame's velocity is relative to its turning axes */
	if (v) {
		vf[0] = v[0] + w[1] * r[2] - w[2] * r[1];
		vf[1] = v[1] + w[2] * r[0] - w[0] * r[2];
		vf[2] = v[2] + w[0] * r[1] - w[1] * r[0];
	}
	for (i = 0; i < 3; i++)
		for (ri[i] = 0.0, j = 0; j < 3; j++)
			ri[i] += m[j][i] * r[j];
	if (v)
		for (i = 0; i < 3; i++)
			for (v[i] = 0.0, j = 0; j < 3; j++)
				v[i] += m[j][i] * vf[j];
	memcpy(r, ri, sizeof(ri));
}

void stray_ccsds_to_inertial(int frame, double t_tt, double r[3],
			     double v[3])
{
	stray_ccsds_to_inertial_cached(NULL, frame, t_tt, r, v);
}

void stray_ccsds_eop_clear(void)
{
	free(eop.mjd);
	free(eop.xp);
	free(eop.yp);
	free(eop.dut1);
	memset(&eop, 0, sizeof(eop));
}

/* Columns [a, b) of line s (1-based a as the IERS layout gives them). */
static int column(const char *s, size_t len, int a, int b, double *x)
{
	char f[16];
	int n = b - a, k = 0;

	if ((size_t)b - 1 > len)
		return 0;
	memcpy(f, s + a - 1, (size_t)n);
	f[n] = '\0';
	while (f[k] == ' ')
		k++;
	return stray_kvn_number(f + k, x);
}

int stray_ccsds_eop_load(const char *path, struct stray_error *err)
{
	char *buf, *s;
	size_t len, cap = 0;
	long line = 0;
	int rc = stray_file_read(path, &buf, &len, err);

	if (rc != STRAY_OK)
		return rc;
	stray_ccsds_eop_clear();
	for (s = buf; s < buf + len && rc == STRAY_OK;) {
		char *e = memchr(s, '\n', (size_t)(buf + len - s));
		size_t l = e ? (size_t)(e - s) : (size_t)(buf + len - s);
		double m, x, y, d;

		line++;
		/* the predicted tail leaves UT1 - UTC blank: the table ends */
		if (!column(s, l, 8, 16, &m) || !column(s, l, 19, 28, &x) ||
		    !column(s, l, 38, 47, &y) || !column(s, l, 59, 69, &d))
			break;
		if (eop.n == cap) {
			size_t c = cap ? 2 * cap : 1024;
			double *p[4] = { realloc(eop.mjd, c * sizeof(double)),
					 NULL, NULL, NULL };

			if (p[0]) eop.mjd = p[0];
			if ((p[1] = realloc(eop.xp, c * sizeof(double)))) eop.xp = p[1];
			if ((p[2] = realloc(eop.yp, c * sizeof(double)))) eop.yp = p[2];
			if ((p[3] = realloc(eop.dut1, c * sizeof(double)))) eop.dut1 = p[3];
			if (!p[0] || !p[1] || !p[2] || !p[3]) {
				rc = stray_error_set(err, STRAY_ENOMEM, "EOP", NULL);
				break;
			}
			cap = c;
		}
		/* the pole stays within 1", UT1 - UTC within 0.9 s */
		if ((eop.n > 0 && !(m > eop.mjd[eop.n - 1])) ||
		    fabs(x) > 1.0 || fabs(y) > 1.0 || fabs(d) > 0.9) {
			rc = stray_error_at(err, STRAY_EPARSE, path, line,
					    "EOP", "not an IERS finals line (MJD increasing, |x_p|, |y_p| <= 1\", |UT1-UTC| <= 0.9 s)");
			break;
		}
		eop.mjd[eop.n] = m;
		eop.xp[eop.n] = x;
		eop.yp[eop.n] = y;
		eop.dut1[eop.n] = d;
		eop.n++;
		s = e ? e + 1 : buf + len;
	}
	if (rc == STRAY_OK && eop.n < 2)
		rc = stray_error_at(err, STRAY_EPARSE, path, line, "EOP",
				    "fewer than 2 IERS finals lines with UT1 - UTC");
	if (rc != STRAY_OK)
		stray_ccsds_eop_clear();
	free(buf);
	return rc;
}
