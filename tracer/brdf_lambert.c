/*
 * brdf_lambert.c - ideal diffuse reflector of hemispherical reflectance
 * rho: f = rho / pi (thesis §3.4: the black anodise, 4 %).
 */
#include <math.h>

#include "tracer/brdf.h"

static double lambert_eval(const struct tracer_brdf *b, struct vec3 wo,
			   struct vec3 wi)
{
	if (wo.z <= 0.0 || wi.z <= 0.0)
		return 0.0;
	return b->rho / M_PI;
}

static int lambert_sample(const struct tracer_brdf *b, struct vec3 wo,
			  double u1, double u2, struct tracer_brdf_sample *s)
{
	if (wo.z <= 0.0)
		return 0;
	/* Sample cosine-weighted hemisphere to compute wi and pdf. */
	s->wi = tracer_sample_cosine_hemisphere(u1, u2);
	s->pdf = tracer_cosine_hemisphere_pdf(s->wi.z);
	if (s->pdf <= 0.0)
		return 0;
	s->f = b->rho / M_PI;
	s->weight = b->rho;	/* f cos / pdf, exactly */
	s->flags = TRACER_BRDF_DIFFUSE;
	return 1;
}

static double lambert_pdf(const struct tracer_brdf *b, struct vec3 wo,
			  struct vec3 wi)
{
	(void)b;
	if (wo.z <= 0.0)
		return 0.0;
	return tracer_cosine_hemisphere_pdf(wi.z);
}

static unsigned lambert_flags(const struct tracer_brdf *b)
{
	(void)b;
	return TRACER_BRDF_DIFFUSE;
}

const struct tracer_brdf_ops tracer_brdf_lambert_ops = {
	"lambert", lambert_eval, lambert_sample, lambert_pdf, lambert_flags
};
