/*
 * truth.c - the hidden-effect generator (truth.h).  Traces the hidden
 * scene directly at the true angles, then applies what a laboratory adds:
 * an additive floor and leak, a multiplicative dip (not in any registry),
 * photometer noise and a detection floor.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/photometry.h"
#include "stray/spectrum_io.h"
#include "tracer/integrator.h"
#include "tracer/paths.h"
#include "tracer/scene_load.h"
#include "truth.h"

void truth_defaults(struct truth_config *c, const double *theta, size_t n)
{
	memset(c, 0, sizeof(*c));
	c->theta_deg = theta;
	c->n = n;
	c->rel_noise = 0.03;
	c->floor_sigma = 1e-7;
	c->seed = 4242;
	c->n_paths = 1000000;
	c->noise_seed = 99;
}

/* splitmix64 (Steele et al. 2014) and Box-Muller: test noise only. */
static double uniform(uint64_t *s)
{
	uint64_t z = (*s += 0x9e3779b97f4a7c15ull);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	z ^= z >> 31;
	return ((z >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double gauss(uint64_t *s)
{
	double u1 = uniform(s), u2 = uniform(s);

	return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

/* A forward-scattering coating of the same hemispherical reflectance:
 * ABg with B = 0.01 and A from Simpson's rule on the normal-incidence
 * total integrated scatter 2 pi int_0^1 r / (B + r^g) dr = 1. */
static void make_abg(struct tracer_scene *s, double g)
{
	const double B = 0.01;
	double sum = 0.0, a;
	int i, n = 2000;
	size_t k;

	for (i = 0; i <= n; i++) {
		double r = (double)i / n, w = i == 0 || i == n ? 1 : i % 2 ? 4 : 2;

		sum += w * r / (B + pow(r, g));
	}
	a = 1.0 / (2.0 * M_PI * sum / (3.0 * n));
	for (k = 0; k < s->mesh.n_group; k++)
		if (s->material[k].ops == &tracer_brdf_lambert_ops) {
			s->material[k].ops = &tracer_brdf_abg_ops;
			s->material[k].abg.a = a;
			s->material[k].abg.b = B;
			s->material[k].abg.g = g;
		}
}

/* Photon weights of the Sun (AM0) x the built-in QE on a 5 nm grid and
 * the two-band coating's moments <rho^k>, k = 0..TRUTH_KMAX: a photon
 * keeps its wavelength through all its bounces. */
#define TRUTH_KMAX 7
static int band_moments(const struct truth_config *c, double *m)
{
	struct stray_spectrum_data sun, qe;
	struct stray_error err;
	double l, sum = 0.0;
	int k, rc;

	memset(&sun, 0, sizeof(sun));
	memset(&qe, 0, sizeof(qe));
	stray_error_clear(&err);
	rc = stray_spectrum_load("builtin:sun_am0_astm_e490", &sun, &err);
	if (!rc)
		rc = stray_spectrum_load("builtin:qe_mt9p031_approx", &qe, &err);
	for (k = 0; k <= TRUTH_KMAX; k++)
		m[k] = 0.0;
	for (l = 250.0; !rc && l <= 1200.0; l += 5.0) {
		double w = stray_spectrum_at(&sun.s, l) *
			   stray_spectrum_at(&qe.s, l) * l,
		       rho = l < c->band_split_nm ? c->band_rho_blue :
			     c->band_rho_red, x = w;

		sum += w;
		for (k = 0; k <= TRUTH_KMAX; k++, x *= rho)
			m[k] += x;
	}
	for (k = 0; !rc && k <= TRUTH_KMAX; k++)
		m[k] /= sum;
	stray_spectrum_data_free(&sun);
	stray_spectrum_data_free(&qe);
	return rc;
}

int truth_band_moments(const struct truth_config *c, double *m, int kmax)
{
	double all[TRUTH_KMAX + 1];
	int k, rc;

	if (kmax < 0 || kmax > TRUTH_KMAX)
		return -1;
	rc = band_moments(c, all);
	for (k = 0; !rc && k <= kmax; k++)
		m[k] = all[k];
	return rc;
}

/* Detector power per traced angle: the tracer's own, or with the
 * two-band coating the direct term plus every recorded path of k
 * Lambertian (interior) vertices x <rho^k> (other vertices keep theirs). */
static int truth_power(const struct truth_config *c,
		       const struct tracer_scene *s,
		       const struct tracer_result *r, double *p, double *sg)
{
	double m[TRUTH_KMAX + 1];
	size_t j, e;
	int b, rc;

	for (j = 0; j < r->n_theta; j++)
		tracer_result_power(r, j, -1, &p[j], &sg[j]);
	if (!(c->band_rho_blue > 0.0))
		return 0;
	rc = band_moments(c, m);
	if (rc)
		return rc;
	for (j = 0; j < r->n_theta; j++) {
		double rel = p[j] > 0.0 ? sg[j] / p[j] : 0.0;

		p[j] = 0.0;
		for (b = 0; b < r->n_batches; b++)
			p[j] += r->power[((size_t)b * r->n_theta + j) *
					 TRACER_ORDERS];
		sg[j] = rel;	/* relative, for now */
	}
	for (e = 0; e < r->paths.cap; e++) {
		const struct tracer_path_entry *pe = &r->paths.e[e];
		int g[TRACER_SEQ_MAX], n, k, n_l = 0;
		double f = 1.0;

		if (!pe->used)
			continue;
		n = tracer_seq_unpack(pe->seq, g);
		for (k = 0; k < n; k++) {
			const struct tracer_brdf *mt = &s->material[g[k]];

			if (mt->ops == &tracer_brdf_lambert_ops)
				n_l++;
			else
				f *= mt->rho;
		}
		p[pe->theta_index] += pe->value * f * m[n_l];
	}
	for (j = 0; j < r->n_theta; j++)
		sg[j] *= p[j];
	return 0;
}

/* The hidden scene traced at every direction of the beam (a sunflower
 * set of TRUTH_DIRS points filling the disk uniformly; one direction
 * when collimated) about each true angle, alpha the ratio of the beam
 * means about theta and about the logged zero. */
#define TRUTH_DIRS 48
static int trace_truth_beam(const struct truth_config *c,
			    struct tracer_scene *s, double *alpha,
			    double *sim_sigma)
{
	struct tracer_trace_opts o;
	struct tracer_result r;
	struct stray_error err;
	int nd = c->beam_half_deg > 0.0 ? TRUTH_DIRS : 1, d, rc;
	size_t i, nt = (c->n + 1) * (size_t)nd;
	double *th = malloc(3 * nt * sizeof(*th)), *p = th + nt, *sg = p + nt;
	double p0 = 0.0, v0 = 0.0;

	if (!th)
		return -1;
	stray_error_clear(&err);
	memset(&r, 0, sizeof(r));
	for (i = 0; i <= c->n; i++)
		for (d = 0; d < nd; d++) {
			double t = (i ? c->theta_deg[i - 1] : 0.0) +
				   c->angle_offset_deg,
			       rr = c->beam_half_deg * sqrt((d + 0.5) / nd),
			       a = d * 2.399963229728653, u = t + rr * cos(a),
			       v = rr * sin(a);

			th[i * nd + d] = sqrt(u * u + v * v);
		}
	tracer_trace_defaults(&o);
	o.theta_deg = th;
	o.n_theta = nt;
	o.n_paths = c->n_paths;
	o.seed = c->seed;
	o.threads = 2;
	o.record_paths = c->band_rho_blue > 0.0;
	rc = tracer_trace(s, &o, &r, &err);
	if (!rc)
		rc = truth_power(c, s, &r, p, sg);
	for (i = 0; !rc && i <= c->n; i++) {
		double sum = 0.0, var = 0.0;

		for (d = 0; d < nd; d++) {	/* r^2 of point d: b^2 (d+.5)/nd */
			double r2 = c->beam_half_deg * c->beam_half_deg *
				    (d + 0.5) / nd,
			       w = c->beam_gauss_deg > 0.0 ?
				   exp(-2.0 * r2 / (c->beam_gauss_deg *
						    c->beam_gauss_deg)) : 1.0;

			sum += w * p[i * nd + d];
			var += w * w * sg[i * nd + d] * sg[i * nd + d];
		}
		if (i == 0) {
			p0 = sum;
			v0 = sum > 0.0 ? var / (sum * sum) : 0.0;
			continue;
		}
		alpha[i - 1] = p0 > 0.0 ? sum / p0 : 0.0;
		sim_sigma[i - 1] = alpha[i - 1] *
			sqrt((sum > 0.0 ? var / (sum * sum) : 0.0) + v0);
	}
	if (rc)
		fprintf(stderr, "truth: %s (%s)\n", err.reason ? err.reason : "",
			err.field ? err.field : "");
	tracer_result_free(&r);
	free(th);
	return rc;
}

static int trace_truth(const struct truth_config *c, double *alpha,
		       double *sim_sigma)
{
	struct tracer_scene s;
	struct tracer_trace_opts o;
	struct tracer_result r;
	struct stray_error err;
	struct tracer_lens lens = { 0, NULL, NULL };
	double th[256];
	size_t i;
	int rc;

	if (c->n + 1 > 256)
		return -1;
	stray_error_clear(&err);
	th[0] = fabs(c->angle_offset_deg);	/* the logged zero, truly */
	for (i = 0; i < c->n; i++)
		th[i + 1] = fabs(c->theta_deg[i] + c->angle_offset_deg);
	tracer_scene_init(&s);
	memset(&r, 0, sizeof(r));
	rc = tracer_scene_load(c->scene ? c->scene : "ref4", c->sets,
			       c->n_sets, &s, &err);
	if (!rc && c->abg_g > 0.0)
		make_abg(&s, c->abg_g);
	for (i = 0; !rc && c->group && i < s.mesh.n_group; i++)
		if (strcmp(s.mesh.group_name[i], c->group) == 0)
			s.material[i].rho *= c->group_factor;
	if (!rc && c->lens)
		rc = tracer_lens_load(c->lens, &lens, &err);
	/* the stage turns about a point behind the aperture: in the baffle's
	 * frame the beam axis passes through it at every angle */
	if (!rc)
		s.beam.center = v3(0.0, 0.0, s.beam.center.z - c->pivot_mm);
	if (!rc)
		rc = tracer_scene_commit(&s, &err);
	if (!rc && (c->beam_half_deg > 0.0 || c->band_rho_blue > 0.0)) {
		rc = trace_truth_beam(c, &s, alpha, sim_sigma);
		tracer_scene_free(&s);
		return rc;
	}
	if (!rc) {
		tracer_trace_defaults(&o);
		o.theta_deg = th;
		o.n_theta = c->n + 1;
		o.n_paths = c->n_paths;
		o.seed = c->seed;
		o.threads = 2;
		o.lens = c->lens ? &lens : NULL;
		rc = tracer_trace(&s, &o, &r, &err);
	}
	for (i = 0; !rc && i < c->n; i++)
		tracer_result_alpha(&r, i + 1, 0, -1, &alpha[i], &sim_sigma[i]);
	if (rc)
		fprintf(stderr, "truth: %s (%s)\n", err.reason ? err.reason : "",
			err.field ? err.field : "");
	tracer_result_free(&r);
	tracer_scene_free(&s);
	tracer_lens_free(&lens);
	return rc;
}

int truth_write(const struct truth_config *c, const char *path)
{
	struct stray_curve out;
	struct stray_error err;
	double a[256], ss[256];
	uint64_t noise = c->noise_seed;
	size_t i;
	int rc = trace_truth(c, a, ss);

	if (rc)
		return rc;
	stray_error_clear(&err);
	if (stray_curve_alloc(&out, c->n, 1, &err))
		return -1;
	for (i = 0; i < c->n; i++) {
		double th = c->theta_deg[i], x = a[i], s;

		x += c->floor;
		if (c->leak_level > 0.0 && th >= c->leak_lo_deg &&
		    th <= c->leak_hi_deg)
			x += c->leak_level;
		if (c->dip_factor > 0.0 && th >= c->dip_lo_deg &&
		    th <= c->dip_hi_deg)
			x *= c->dip_factor;
		s = sqrt(pow(c->rel_noise * x, 2) + pow(c->floor_sigma, 2) +
			 pow(ss[i], 2));
		out.theta_deg[i] = th;
		if (th == 0.0) {	/* the normalisation point */
			out.alpha[i] = 1.0;
			out.sigma[i] = 1e-3;
			continue;
		}
		x += c->rel_noise * x * gauss(&noise) +
		     c->floor_sigma * gauss(&noise);
		out.alpha[i] = fmax(x, c->floor_sigma);	/* detection floor */
		out.sigma[i] = s;
	}
	rc = stray_curve_save(path, &out, &err);
	stray_curve_free(&out);
	return rc;
}
