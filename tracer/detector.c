/*
 * detector.c - detector sampling and the lens transmission table.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/lens_model.h"
#include "tracer/brdf.h"
#include "tracer/detector.h"

double tracer_detector_area(const struct tracer_detector *d)
{
	if (d->shape == TRACER_DET_DISK)
		return M_PI * d->radius_mm * d->radius_mm;
	return 4.0 * d->half_w_mm * d->half_h_mm;
}

struct vec3 tracer_detector_sample_point(const struct tracer_detector *d,
					 double u1, double u2)
{
	struct frame f = frame_from_normal(d->normal);
	double x, y;

	if (d->shape == TRACER_DET_DISK) {
		tracer_sample_disk(u1, u2, &x, &y);
		x *= d->radius_mm;
		y *= d->radius_mm;
	} else {
		x = (2.0 * u1 - 1.0) * d->half_w_mm;
		y = (2.0 * u2 - 1.0) * d->half_h_mm;
	}
	return v3_add(d->center, v3_add(v3_scale(f.s, x), v3_scale(f.t, y)));
}

static double sin2_accept(const struct tracer_detector *d)
{
	double a = d->accept_half_angle_deg;

	if (a <= 0.0 || a >= 90.0)
		return 1.0;
	a *= M_PI / 180.0;
	return sin(a) * sin(a);
}

double tracer_detector_proj_solid_angle(const struct tracer_detector *d)
{
	return M_PI * sin2_accept(d);
}

struct vec3 tracer_detector_sample_dir(const struct tracer_detector *d,
				       double u1, double u2,
				       double *proj_solid_angle)
{
	/* Cosine-weighted inside the cone: a uniform point on the disk of
	 * radius sin(half angle), lifted (Malley's method restricted). */
	struct frame f = frame_from_normal(d->normal);
	double s2 = sin2_accept(d), x, y, z2;

	tracer_sample_disk(u1, u2, &x, &y);
	x *= sqrt(s2);
	y *= sqrt(s2);
	z2 = 1.0 - x * x - y * y;
	*proj_solid_angle = tracer_detector_proj_solid_angle(d);
	return frame_to_world(&f, v3(x, y, z2 > 0.0 ? sqrt(z2) : 0.0));
}

void tracer_detector_dir_inverse(const struct tracer_detector *d,
				 struct vec3 w, double *u1, double *u2)
{
	struct frame f = frame_from_normal(d->normal);
	struct vec3 l = frame_to_local(&f, w);
	double k = 1.0 / sqrt(sin2_accept(d));

	tracer_sample_disk_inverse(l.x * k, l.y * k, u1, u2);
}

int tracer_detector_accepts(const struct tracer_detector *d, struct vec3 w)
{
	double c = v3_dot(w, d->normal);

	if (c <= 0.0)
		return 0;
	return 1.0 - c * c <= sin2_accept(d);
}

int tracer_detector_check(const struct tracer_detector *d,
			  struct stray_error *err)
{
	if (fabs(v3_len(d->normal) - 1.0) > 1e-9)
		return stray_error_set(err, STRAY_EINVAL, "detector.normal",
				       "must be a unit vector");
	if (d->shape == TRACER_DET_DISK && !(d->radius_mm > 0.0))
		return stray_error_set_value(err, STRAY_EINVAL,
					     "detector.radius_mm",
					     "must be positive", d->radius_mm);
	if (d->shape == TRACER_DET_RECT &&
	    !(d->half_w_mm > 0.0 && d->half_h_mm > 0.0))
		return stray_error_set(err, STRAY_EINVAL, "detector.size_mm",
				       "must be positive");
	return STRAY_OK;
}

double tracer_lens_transmission(const struct tracer_lens *lens,
				double theta_deg)
{
	size_t lo = 0, hi;

	if (!lens || lens->n == 0)
		return 1.0;
	hi = lens->n - 1;
	if (theta_deg <= lens->theta_deg[0])
		return lens->t[0];
	if (theta_deg >= lens->theta_deg[hi])
		return lens->t[hi];	/* thesis §3.4.4: last value beyond */
	while (hi - lo > 1) {
		size_t mid = (lo + hi) / 2;

		if (lens->theta_deg[mid] <= theta_deg)
			lo = mid;
		else
			hi = mid;
	}
	return lens->t[lo] + (lens->t[hi] - lens->t[lo]) *
	       (theta_deg - lens->theta_deg[lo]) /
	       (lens->theta_deg[hi] - lens->theta_deg[lo]);
}

/* "ideal:DEG": the ideal lens of that field half-angle (lens_model.h). */
static int ideal_lens(const char *spec, struct stray_curve *c,
		      struct stray_error *err)
{
	char *end;
	double field = strtod(spec + 6, &end);

	if (end == spec + 6 || *end) {
		stray_error_set(err, STRAY_EINVAL, "--lens",
			"ideal:DEG, DEG the lens's field half-angle in degrees");
		stray_error_text(err, spec);
		return STRAY_EINVAL;
	}
	return stray_lens_ideal(field, c, err);
}

int tracer_lens_load(const char *path, struct tracer_lens *lens,
		     struct stray_error *err)
{
	struct stray_curve c;
	int rc;

	memset(lens, 0, sizeof(*lens));
	rc = strncmp(path, "ideal:", 6) == 0 ? ideal_lens(path, &c, err)
					     : stray_curve_load(path, &c, err);
	if (rc)
		return rc;
	lens->theta_deg = malloc(c.n * sizeof(double));
	lens->t = malloc(c.n * sizeof(double));
	if (!lens->theta_deg || !lens->t) {
		tracer_lens_free(lens);
		stray_curve_free(&c);
		return stray_error_set(err, STRAY_ENOMEM, "lens",
				       "out of memory");
	}
	memcpy(lens->theta_deg, c.theta_deg, c.n * sizeof(double));
	memcpy(lens->t, c.alpha, c.n * sizeof(double));
	lens->n = c.n;
	stray_curve_free(&c);
	return STRAY_OK;
}

void tracer_lens_free(struct tracer_lens *lens)
{
	free(lens->theta_deg);
	free(lens->t);
	memset(lens, 0, sizeof(*lens));
}
