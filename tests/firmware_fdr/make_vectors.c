/*
 * make_vectors.c - writes tests/vectors/fdrfw_curve.csv and
 * tests/vectors/fdrfw_vectors.h: random frames and what ground libstray,
 * in double precision and without any firmware code, expects of them.
 * Run by `make fdrfw-vectors`; its output is checked in.
 *
 * Truth per frame: angles from the double attitude; alpha by
 * stray_curve_alpha_at; FDR by stray_fdr_threshold and stray_fdr_log_rate
 * (eq. 2.16-2.18); flags by stray_fdr_alpha_required and
 * stray_exclusion_angle (fig. 2.7, 5.1) for the frame's exposure and the
 * Moon's phase (stray_moon_mag_at_phase); frames within 0.01 deg of an
 * edge are skipped, as float angles may fall either side.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"
#include "stray/curve_io.h"
#include "stray/fdr.h"
#include "stray/photometry.h"
#include "stray/sensor.h"
#include "vectors.h"

#define N_VECTORS 200
#define EDGE_DEG 0.01
#define DEG 0.017453292519943295

static uint64_t rng = 0x9E3779B97F4A7C15u;

static double uniform(void)	/* xorshift64*: reproducible everywhere */
{
	rng ^= rng >> 12;
	rng ^= rng << 25;
	rng ^= rng >> 27;
	return (double)((rng * 2685821657736338717u) >> 11) / 9007199254740992.0;
}

static void unit(double v[3])
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	v[0] /= n; v[1] /= n; v[2] /= n;
}

/* A direction theta_deg from b, at a random azimuth. */
static void off_axis(const double b[3], double theta_deg, double out[3])
{
	double a[3] = { 0.3, -0.5, 0.8 }, e1[3], e2[3], phi = 2 * M_PI * uniform();
	double t = theta_deg * DEG;
	int i;

	e1[0] = b[1] * a[2] - b[2] * a[1];
	e1[1] = b[2] * a[0] - b[0] * a[2];
	e1[2] = b[0] * a[1] - b[1] * a[0];
	unit(e1);
	e2[0] = b[1] * e1[2] - b[2] * e1[1];
	e2[1] = b[2] * e1[0] - b[0] * e1[2];
	e2[2] = b[0] * e1[1] - b[1] * e1[0];
	for (i = 0; i < 3; i++)
		out[i] = cos(t) * b[i] + sin(t) * (cos(phi) * e1[i] +
						   sin(phi) * e2[i]);
}

static double angle(const double a[3], const float f[3])
{
	double b[3] = { f[0], f[1], f[2] }, c[3];

	unit(b);
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
	return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
		     a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / DEG;
}

/* ln FDR at theta and the exclusion angle, for flux f and exposure t. */
static void ground(double f, double t_exp, double theta, double *ln_fdr,
		   double *theta_x)
{
	const struct stray_curve_view *c = fixture_curve();
	struct stray_fdr_model m;
	double i_sdt, req;
	int rc;

	stray_sensor_fdr_model(stray_sensor_st16_like(), f,
			       fixture_fluxes()->drs, &m);
	m.t_exp_s = t_exp;
	rc = stray_fdr_threshold(&m, &i_sdt, NULL);
	rc |= stray_fdr_log_rate(&m, stray_curve_alpha_at(c, theta), i_sdt,
				 ln_fdr, NULL);
	rc |= stray_fdr_alpha_required(&m, 5.0, &req, NULL);
	if (rc || stray_exclusion_angle(c, req, theta_x, NULL) != 0)
		*theta_x = NAN;	/* not excluded within the curve */
}

static int near(double a, double b)
{
	return fabs(a - b) < EDGE_DEG;
}

/* One random frame; 0 when it lies too near an edge to be a fair test. */
static int make_one(struct fdrfw_vector *v)
{
	static const float t_exp[] = { 0.02f, 0.1f, 0.1f, 0.4f };
	double q[4], b[3], s[3], mo[3], nq = 0, xs, xm, fov, f_moon, phase;
	double m_full = stray_sensor_st16_like()->moon_mag;
	int i;

	for (i = 0; i < 4; i++) {	/* random attitude */
		q[i] = uniform() - 0.5;
		nq += q[i] * q[i];
	}
	for (i = 0; i < 4; i++)
		v->q[i] = (float)(q[i] / sqrt(nq));
	for (i = 0, nq = 0; i < 4; i++)
		nq += (double)v->q[i] * v->q[i];
	for (i = 0; i < 4; i++)
		q[i] = v->q[i] / sqrt(nq);
	b[0] = 2 * (q[1] * q[3] - q[0] * q[2]);	/* third row of R(q) */
	b[1] = 2 * (q[2] * q[3] + q[0] * q[1]);
	b[2] = 1 - 2 * (q[1] * q[1] + q[2] * q[2]);
	off_axis(b, 70.0 * uniform(), s);
	off_axis(b, 30.0 * uniform(), mo);
	for (i = 0; i < 3; i++) {
		v->sun_dir[i] = (float)s[i];
		v->moon_dir[i] = (float)mo[i];
		v->pos_km[i] = (float)(1.0e6 * s[i]);	/* Earth: night side */
	}
	v->t_exp_s = t_exp[(int)(4 * uniform()) & 3];
	v->theta_deg[0] = angle(b, v->sun_dir);
	v->theta_deg[1] = angle(b, v->moon_dir);
	phase = 180.0 - angle(s, v->moon_dir);
	f_moon = fixture_fluxes()->moon *
		 pow(10.0, -0.4 * (stray_moon_mag_at_phase(m_full, phase) - m_full));
	ground(fixture_fluxes()->sun, v->t_exp_s, v->theta_deg[0],
	       &v->ln_fdr[0], &xs);
	ground(f_moon, v->t_exp_s, v->theta_deg[1], &v->ln_fdr[1], &xm);
	fov = stray_sensor_st16_like()->fov_half_deg;
	if (near(v->theta_deg[0], xs) || near(v->theta_deg[1], xm) ||
	    near(v->theta_deg[0], fov + FDRFW_SUN_RADIUS_DEG) ||
	    near(v->theta_deg[1], fov + FDRFW_MOON_RADIUS_DEG))
		return 0;
	v->flags = 0;
	if (v->theta_deg[0] < xs)
		v->flags |= FDRFW_SUN_EXCLUDED;
	if (v->theta_deg[1] < xm ||
	    v->theta_deg[1] < fov + FDRFW_MOON_RADIUS_DEG)
		v->flags |= FDRFW_MOON_EXCLUDED;
	if (v->theta_deg[0] < fov + FDRFW_SUN_RADIUS_DEG)
		v->flags |= FDRFW_SUN_IN_FOV;
	if (v->theta_deg[1] < fov + FDRFW_MOON_RADIUS_DEG)
		v->flags |= FDRFW_MOON_IN_FOV;
	return 1;
}

static void print_floats(FILE *f, const float *v, int n)
{
	int i;

	fputs("{ ", f);
	for (i = 0; i < n; i++)
		fprintf(f, "%s%af", i ? ", " : "", (double)v[i]);
	fputs(" }", f);
}

static int write_vectors(const char *path)
{
	FILE *f = fopen(path, "w");
	struct fdrfw_vector v;
	int n = 0;

	if (!f)
		return 1;
	fputs("/* Generated by tests/firmware_fdr/make_vectors.c "
	      "(make fdrfw-vectors): do not edit. */\n"
	      "static const struct fdrfw_vector fdrfw_vectors[] = {\n", f);
	while (n < N_VECTORS) {
		if (!make_one(&v))
			continue;
		fputs("\t{ ", f);
		print_floats(f, v.q, 4);
		fprintf(f, ", %af, ", (double)v.t_exp_s);
		print_floats(f, v.pos_km, 3);
		fputs(", ", f);
		print_floats(f, v.sun_dir, 3);
		fputs(", ", f);
		print_floats(f, v.moon_dir, 3);
		fprintf(f, ",\n\t  { %a, %a }, { %a, %a }, 0x%02lxu },\n",
			v.theta_deg[0], v.theta_deg[1], v.ln_fdr[0],
			v.ln_fdr[1], (unsigned long)v.flags);
		n++;
	}
	fputs("};\n", f);
	return fclose(f) != 0;
}

static int write_curve(const char *path)
{
	const struct stray_curve_view *v = fixture_curve();
	struct stray_curve c;
	struct stray_error err;
	size_t i;
	int rc;

	stray_error_clear(&err);
	if (stray_curve_alloc(&c, v->n, 0, &err) != 0)
		return 1;
	for (i = 0; i < v->n; i++) {
		c.theta_deg[i] = v->theta_deg[i];
		c.alpha[i] = v->alpha[i];
	}
	rc = stray_curve_add_meta(&c, "kind", "system", &err);
	rc |= stray_curve_add_meta(&c, "source",
		"tests/firmware_fdr/fixture.c (ref4-like, synthetic)", &err);
	rc |= stray_curve_save(path, &c, &err);
	stray_curve_free(&c);
	return rc;
}

int main(int argc, char **argv)
{
	if (argc != 3) {
		fprintf(stderr, "usage: make_vectors CURVE.csv VECTORS.h\n");
		return 2;
	}
	if (write_curve(argv[1]) || write_vectors(argv[2])) {
		fprintf(stderr, "make_vectors: cannot write %s or %s\n",
			argv[1], argv[2]);
		return 1;
	}
	return 0;
}
