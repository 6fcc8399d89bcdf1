/*
 * detector.h - the detector (lens entrance pupil) and the lens.
 *
 * A disk or rectangle that accepts light from its front (+normal) side,
 * optionally only within an acceptance half-angle (a photometer, thesis
 * §4).  The lens is an angle-dependent transmission table, the lab lens
 * curve of thesis §3.4.4: linear interpolation in the incidence angle,
 * clamped to the end values.
 */
#ifndef TRACER_DETECTOR_H
#define TRACER_DETECTOR_H

#include <stddef.h>

#include "stray/error.h"
#include "tracer/vec.h"

enum tracer_detector_shape { TRACER_DET_DISK, TRACER_DET_RECT };

struct tracer_detector {
	enum tracer_detector_shape shape;
	struct vec3 center, normal;	/* normal: the accepting side */
	double radius_mm;		/* disk */
	double half_w_mm, half_h_mm;	/* rectangle, along frame s and t */
	double accept_half_angle_deg;	/* <= 0 or >= 90: whole hemisphere */
};

struct tracer_lens {
	size_t n;
	double *theta_deg;	/* incidence angle, increasing */
	double *t;		/* transmission */
};

/* Detector area, mm^2. */
double tracer_detector_area(const struct tracer_detector *d);

/* A uniform point on the detector from two uniform numbers. */
struct vec3 tracer_detector_sample_point(const struct tracer_detector *d,
					 double u1, double u2);

/*
 * A direction of incidence (pointing away from the detector, into the
 * scene), cosine-weighted within the acceptance cone; *proj_solid_angle
 * is the cone's projected solid angle pi sin^2(half angle), so the
 * estimate of the integral of L cos over the cone is it times L.
 */
struct vec3 tracer_detector_sample_dir(const struct tracer_detector *d,
				       double u1, double u2,
				       double *proj_solid_angle);

/* The (u1, u2) that tracer_detector_sample_dir maps to direction w (a
 * direction the detector accepts): where a path arriving along w lies in
 * primary-sample space, for the guide's density of it. */
/* The acceptance cone's projected solid angle, pi sin^2(half angle). */
double tracer_detector_proj_solid_angle(const struct tracer_detector *d);

void tracer_detector_dir_inverse(const struct tracer_detector *d,
				 struct vec3 w, double *u1, double *u2);

/* Whether light arriving from direction w (away from the detector) counts. */
int tracer_detector_accepts(const struct tracer_detector *d, struct vec3 w);

/* Check the fields; errors name the field and value. */
int tracer_detector_check(const struct tracer_detector *d,
			  struct stray_error *err);

/* Lens transmission at incidence angle theta_deg; 1 when lens is NULL. */
double tracer_lens_transmission(const struct tracer_lens *lens,
				double theta_deg);

/* The lens from an attenuation-curve CSV (theta_deg, alpha), or
 * "ideal:DEG": the ideal lens of field half-angle DEG (cos^4 inside, 0
 * beyond; stray/lens_model.h).  A file of that name is given as ./ideal:.. */
int tracer_lens_load(const char *path, struct tracer_lens *lens,
		     struct stray_error *err);

void tracer_lens_free(struct tracer_lens *lens);

#endif /* TRACER_DETECTOR_H */
