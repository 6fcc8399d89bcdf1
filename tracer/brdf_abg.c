/*
 * brdf_abg.c - the ABg (Harvey) scatter model of stray-light codes:
 * BSDF(beta - beta0) = rho * A / (B + |beta - beta0|^g), with beta the
 * projection of wi on the surface plane and beta0 that of the specular
 * direction of wo (Harvey 1976; Pfisterer, "Bidirectional scatter
 * distribution function models", in: Breault Research, ASAP manual; and
 * Fest, "Stray light analysis and control", SPIE 2013, ch. 5).
 *
 * Sampling is a mixture: half cosine-weighted, half a Cauchy-like lobe
 * around beta0 in the projected (beta) plane, where cos(theta_i) d omega
 * = d beta makes the change of measure exact.  The lobe density is
 * p(r) = 1 / (pi ln(1 + R^2/c^2) (c^2 + r^2)) on the disk r < R = 2 around
 * beta0, c the knee B^(1/g).
 */
#include <math.h>

#include "tracer/brdf.h"

#define ABG_RMAX 2.0		/* beta0 and beta both lie in the unit disk */
#define ABG_KNEE_MIN 1e-4

static double abg_knee(const struct tracer_abg *p)
{
	double c = p->g > 0.0 ? pow(p->b, 1.0 / p->g) : 1.0;

	return c > ABG_KNEE_MIN ? c : ABG_KNEE_MIN;
}

static double abg_eval(const struct tracer_brdf *b, struct vec3 wo,
		       struct vec3 wi)
{
	double dx, dy, r;

	if (wo.z <= 0.0 || wi.z <= 0.0)
		return 0.0;
	dx = wi.x + wo.x;	/* beta - beta0, beta0 = (-wo.x, -wo.y) */
	dy = wi.y + wo.y;
	r = sqrt(dx * dx + dy * dy);
	return b->rho * b->abg.a / (b->abg.b + pow(r, b->abg.g));
}

/* Density of the lobe in the beta plane at distance r from beta0. */
static double lobe_pdf_beta(double c, double r)
{
	double norm = M_PI * log(1.0 + ABG_RMAX * ABG_RMAX / (c * c));

	return r <= ABG_RMAX ? 1.0 / (norm * (c * c + r * r)) : 0.0;
}

static double abg_pdf(const struct tracer_brdf *b, struct vec3 wo,
		      struct vec3 wi)
{
	double dx, dy, c;

	if (wo.z <= 0.0 || wi.z <= 0.0)
		return 0.0;
	dx = wi.x + wo.x;
	dy = wi.y + wo.y;
	c = abg_knee(&b->abg);
	/* d beta = cos(theta_i) d omega turns the lobe density to solid angle */
	return 0.5 * tracer_cosine_hemisphere_pdf(wi.z) +
	       0.5 * lobe_pdf_beta(c, sqrt(dx * dx + dy * dy)) * wi.z;
}

/* Invert the lobe's radial CDF ln(1 + r^2/c^2) / ln(1 + R^2/c^2). */
static int sample_lobe(double c, struct vec3 wo, double u1, double u2,
		       struct vec3 *wi)
{
	double span = 1.0 + ABG_RMAX * ABG_RMAX / (c * c);
	double r = c * sqrt(pow(span, u1) - 1.0);
	double bx = -wo.x + r * cos(2.0 * M_PI * u2);
	double by = -wo.y + r * sin(2.0 * M_PI * u2);
	double z2 = 1.0 - bx * bx - by * by;

	if (z2 <= 0.0)
		return 0;	/* outside the unit disk: no direction */
	*wi = v3(bx, by, sqrt(z2));
	return 1;
}

static int abg_sample(const struct tracer_brdf *b, struct vec3 wo,
		      double u1, double u2, struct tracer_brdf_sample *s)
{
	if (wo.z <= 0.0)
		return 0;
	/* Pick the mixture component with u1, then reuse it rescaled. */
	if (u1 < 0.5) {
		s->wi = tracer_sample_cosine_hemisphere(2.0 * u1, u2);
	} else if (!sample_lobe(abg_knee(&b->abg), wo, 2.0 * u1 - 1.0, u2,
				&s->wi)) {
		return 0;
	}
	s->pdf = abg_pdf(b, wo, s->wi);
	if (s->pdf <= 0.0)
		return 0;
	s->f = abg_eval(b, wo, s->wi);
	s->weight = s->f * s->wi.z / s->pdf;
	s->flags = TRACER_BRDF_GLOSSY;
	return 1;
}

static unsigned abg_flags(const struct tracer_brdf *b)
{
	(void)b;
	return TRACER_BRDF_GLOSSY;
}

const struct tracer_brdf_ops tracer_brdf_abg_ops = {
	"abg", abg_eval, abg_sample, abg_pdf, abg_flags
};
