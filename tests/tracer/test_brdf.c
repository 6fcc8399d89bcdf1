/*
 * test_brdf.c - the BRDFs: each sampler against its own pdf (chi-square
 * over a (cos theta, phi) grid, as pbrt-v4's Chi2Test), energy
 * conservation (albedo <= 1; Lambert's equal to rho), sample weights
 * against a quadrature of f cos, reciprocity, and the mirror's delta lobe.
 */
#include <stdlib.h>
#include <string.h>

#include "tracer_test.h"
#include "tracer/rng.h"

#define N_COS 10
#define N_PHI 20
#define N_SAMPLES 200000

static struct vec3 dir_of(double cos_t, double phi)
{
	double s = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));

	return v3(s * cos(phi), s * sin(phi), cos_t);
}

/* Expected bin probabilities: the pdf integrated by a fine midpoint rule
 * (d omega = d cos d phi). */
static void expected_bins(const struct tracer_brdf *b, struct vec3 wo,
			  double *e)
{
	const int sub = 12;
	int i, j, k, l;

	for (i = 0; i < N_COS; i++)
		for (j = 0; j < N_PHI; j++) {
			double sum = 0.0;

			for (k = 0; k < sub; k++)
				for (l = 0; l < sub; l++) {
					double c = (i + (k + 0.5) / sub) / N_COS;
					double p = 2.0 * M_PI *
						   (j + (l + 0.5) / sub) / N_PHI;

					sum += b->ops->pdf(b, wo, dir_of(c, p));
				}
			e[i * N_PHI + j] = sum / (sub * sub) *
					   (1.0 / N_COS) * (2.0 * M_PI / N_PHI);
		}
}

/* Chi-square of sampled counts against the pdf, small bins pooled. */
static void chi2_check(const struct tracer_brdf *b, struct vec3 wo)
{
	static double obs[N_COS * N_PHI], e[N_COS * N_PHI];
	double chi2 = 0.0, pool_o = 0.0, pool_e = 0.0;
	struct tracer_rng rng;
	int i, dof = -1, n_ok = 0;

	memset(obs, 0, sizeof(obs));
	expected_bins(b, wo, e);
	tracer_rng_init(&rng, 99, 1);
	for (i = 0; i < N_SAMPLES; i++) {
		struct tracer_brdf_sample s;
		double u1 = tracer_rng_uniform(&rng);
		double u2 = tracer_rng_uniform(&rng), phi;
		int ci, pj;

		if (!b->ops->sample(b, wo, u1, u2, &s))
			continue;
		n_ok++;
		phi = atan2(s.wi.y, s.wi.x);
		if (phi < 0.0)
			phi += 2.0 * M_PI;
		ci = (int)(s.wi.z * N_COS);
		pj = (int)(phi / (2.0 * M_PI) * N_PHI);
		obs[(ci < N_COS ? ci : N_COS - 1) * N_PHI +
		    (pj < N_PHI ? pj : N_PHI - 1)] += 1.0;
	}
	for (i = 0; i < N_COS * N_PHI; i++) {
		double ex = e[i] * N_SAMPLES;

		if (ex < 5.0) {
			pool_o += obs[i];
			pool_e += ex;
			continue;
		}
		chi2 += (obs[i] - ex) * (obs[i] - ex) / ex;
		dof++;
	}
	if (pool_e >= 5.0) {
		chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
		dof++;
	}
	/* failed samples carry the missing pdf mass (lobe outside the disk) */
	assert_true(n_ok > N_SAMPLES / 2);
	if (chi2 > dof + 5.0 * sqrt(2.0 * dof))
		fail_msg("%s: chi2 %.1f for %d dof", b->ops->name, chi2, dof);
}

static const struct tracer_brdf lambert = { &tracer_brdf_lambert_ops, 0.3,
					    { 0, 0, 0 } };
static const struct tracer_brdf abg = { &tracer_brdf_abg_ops, 1.0,
					{ 0.01, 0.01, 2.0 } };

static void test_brdf_lambert_sampler_matches_pdf(void **state)
{
	(void)state;
	chi2_check(&lambert, dir_of(0.7, 1.0));
}

static void test_brdf_abg_sampler_matches_pdf(void **state)
{
	(void)state;
	chi2_check(&abg, dir_of(0.9, 0.3));
	chi2_check(&abg, dir_of(0.3, 2.0));
}

/* Albedo by sampling (mean weight) and by quadrature of f cos. */
static void albedo(const struct tracer_brdf *b, struct vec3 wo,
		   double *by_sampling, double *sigma, double *by_quad)
{
	struct tracer_rng rng;
	const int n = 100000, nq = 400;
	double m = 0, m2 = 0, q = 0;
	int i, j;

	tracer_rng_init(&rng, 5, 2);
	for (i = 0; i < n; i++) {
		struct tracer_brdf_sample s;
		double u1 = tracer_rng_uniform(&rng);
		double w = b->ops->sample(b, wo, u1, tracer_rng_uniform(&rng),
					  &s) ? s.weight : 0.0;

		m += w;
		m2 += w * w;
	}
	*by_sampling = m / n;
	*sigma = sqrt((m2 / n - *by_sampling * *by_sampling) / n);
	/* projected disk: f cos d omega = f d beta, midpoint over a grid */
	for (i = 0; i < nq; i++)
		for (j = 0; j < nq; j++) {
			double x = -1.0 + 2.0 * (i + 0.5) / nq;
			double y = -1.0 + 2.0 * (j + 0.5) / nq;

			if (x * x + y * y < 1.0)
				q += b->ops->eval(b, wo, v3(x, y,
					sqrt(1.0 - x * x - y * y)));
		}
	*by_quad = q * 4.0 / ((double)nq * nq);
}

static void test_brdf_energy_conservation(void **state)
{
	double s, sg, q;

	(void)state;
	albedo(&lambert, dir_of(0.5, 0.0), &s, &sg, &q);
	assert_near(s, 0.3, 1e-12);	/* Lambert: exactly rho */
	assert_near(q, 0.3, 3e-3);
	albedo(&abg, dir_of(0.8, 0.0), &s, &sg, &q);
	assert_true(s < 1.0 && q < 1.0);
	assert_near(s, q, 5.0 * sg + 0.01 * q);
	albedo(&abg, dir_of(0.2, 0.0), &s, &sg, &q);
	assert_near(s, q, 5.0 * sg + 0.01 * q);
}

static void test_brdf_reciprocity(void **state)
{
	struct vec3 a = dir_of(0.8, 0.4), b = dir_of(0.35, 2.5);

	(void)state;
	assert_near(lambert.ops->eval(&lambert, a, b),
		    lambert.ops->eval(&lambert, b, a), 1e-15);
	assert_near(abg.ops->eval(&abg, a, b), abg.ops->eval(&abg, b, a),
		    1e-12);
	/* ABg peaks in the specular direction */
	assert_true(abg.ops->eval(&abg, a, v3(-a.x, -a.y, a.z)) >
		    abg.ops->eval(&abg, a, b));
}

static void test_brdf_mirror_is_a_delta(void **state)
{
	const struct tracer_brdf m = { &tracer_brdf_mirror_ops, 0.9,
				       { 0, 0, 0 } };
	struct tracer_brdf_sample s;
	struct vec3 wo = dir_of(0.6, 1.2);

	(void)state;
	assert_true(m.ops->sample(&m, wo, 0.3, 0.7, &s));
	assert_near(s.wi.x, -wo.x, 1e-15);
	assert_near(s.wi.y, -wo.y, 1e-15);
	assert_near(s.wi.z, wo.z, 1e-15);
	assert_near(s.weight, 0.9, 1e-15);
	assert_true(s.flags & TRACER_BRDF_SPECULAR);
	assert_true(m.ops->eval(&m, wo, s.wi) == 0.0);
	assert_true(m.ops->pdf(&m, wo, s.wi) == 0.0);
	/* below the surface nothing is sampled */
	assert_false(m.ops->sample(&m, v3(0, 0, -1), 0.3, 0.7, &s));
	assert_false(lambert.ops->sample(&lambert, v3(0, 0, -1), 0.3, 0.7, &s));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_brdf_lambert_sampler_matches_pdf),
		cmocka_unit_test(test_brdf_abg_sampler_matches_pdf),
		cmocka_unit_test(test_brdf_energy_conservation),
		cmocka_unit_test(test_brdf_reciprocity),
		cmocka_unit_test(test_brdf_mirror_is_a_delta),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
