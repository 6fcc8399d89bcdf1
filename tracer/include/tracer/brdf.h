/*
 * brdf.h - surface scattering, one interface with one file per family
 * (pbrt-v4's BxDF: f / Sample_f / PDF / Flags).
 *
 * Everything is in the local shading frame, normal = +z, both directions
 * pointing away from the surface: wo toward where the light goes (the
 * detector side of a path), wi toward where it comes from.  Grey scalar
 * BRDFs in sr^-1.  Every BRDF is a reflectance scale `rho` times a shape,
 * so recorded path weights can be re-weighted by rho^k without re-tracing
 * (../shared/docs/method.md §6: the reflectance was the model's main error).
 * `sample` takes two uniform numbers from the caller, never an RNG, so
 * tests drive it exactly.
 */
#ifndef TRACER_BRDF_H
#define TRACER_BRDF_H

#include "tracer/vec.h"

enum tracer_brdf_flags {
	TRACER_BRDF_DIFFUSE = 1u << 0,	/* smooth in wi: next-event usable */
	TRACER_BRDF_SPECULAR = 1u << 1,	/* delta lobe: reached by sample only */
	TRACER_BRDF_GLOSSY = 1u << 2
};

struct tracer_brdf_sample {
	struct vec3 wi;		/* sampled direction (local, wi.z > 0) */
	double f;		/* BRDF value (0 for a delta lobe) */
	double pdf;		/* solid-angle pdf (0 for a delta lobe) */
	double weight;		/* f cos(theta_i) / pdf, or R for a delta lobe */
	unsigned flags;
};

struct tracer_brdf;

struct tracer_brdf_ops {
	const char *name;
	double (*eval)(const struct tracer_brdf *b, struct vec3 wo,
		       struct vec3 wi);
	/* 1 and a sample, or 0 when no direction was produced. */
	int (*sample)(const struct tracer_brdf *b, struct vec3 wo, double u1,
		      double u2, struct tracer_brdf_sample *s);
	double (*pdf)(const struct tracer_brdf *b, struct vec3 wo,
		      struct vec3 wi);
	unsigned (*flags)(const struct tracer_brdf *b);
};

/* ABg (Harvey) parameters: BSDF = A / (B + |beta - beta0|^g). */
struct tracer_abg {
	double a, b, g;
};

struct tracer_brdf {
	const struct tracer_brdf_ops *ops;	/* NULL: a perfect absorber */
	double rho;		/* reflectance scale (Lambert: hemispherical) */
	struct tracer_abg abg;
};

extern const struct tracer_brdf_ops tracer_brdf_lambert_ops;
extern const struct tracer_brdf_ops tracer_brdf_mirror_ops;
extern const struct tracer_brdf_ops tracer_brdf_abg_ops;

/* Cosine-weighted hemisphere sampling and its pdf, side by side. */
struct vec3 tracer_sample_cosine_hemisphere(double u1, double u2);
double tracer_cosine_hemisphere_pdf(double cos_theta);

/* Uniform point on the unit disk (concentric map, Shirley-Chiu 1997). */
void tracer_sample_disk(double u1, double u2, double *x, double *y);
/* Its inverse: the (u1, u2) that tracer_sample_disk maps to (x, y). */
void tracer_sample_disk_inverse(double x, double y, double *u1, double *u2);

#endif /* TRACER_BRDF_H */
