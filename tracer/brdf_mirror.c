/*
 * brdf_mirror.c - specular reflector of reflectance rho (the mirror-coated
 * exterior of thesis §3.4: light that misses the aperture leaves).  A delta
 * lobe: eval and pdf are 0, only sample reaches it.
 */
#include "tracer/brdf.h"

static double mirror_eval(const struct tracer_brdf *b, struct vec3 wo,
			  struct vec3 wi)
{
	(void)b;
	(void)wo;
	(void)wi;
	return 0.0;
}

static int mirror_sample(const struct tracer_brdf *b, struct vec3 wo,
			 double u1, double u2, struct tracer_brdf_sample *s)
{
	(void)u1;
	(void)u2;
	if (wo.z <= 0.0)
		return 0;
	s->wi = v3(-wo.x, -wo.y, wo.z);
	s->f = 0.0;
	s->pdf = 0.0;
	s->weight = b->rho;
	s->flags = TRACER_BRDF_SPECULAR;
	return 1;
}

static double mirror_pdf(const struct tracer_brdf *b, struct vec3 wo,
			 struct vec3 wi)
{
	(void)b;
	(void)wo;
	(void)wi;
	return 0.0;
}

static unsigned mirror_flags(const struct tracer_brdf *b)
{
	(void)b;
	return TRACER_BRDF_SPECULAR;
}

const struct tracer_brdf_ops tracer_brdf_mirror_ops = {
	"mirror", mirror_eval, mirror_sample, mirror_pdf, mirror_flags
};
