/*
 * vec.h - the small 3-vector algebra the tracer needs (double precision;
 * Embree sees floats only at the ray-query boundary, scene_embree.c).
 */
#ifndef TRACER_VEC_H
#define TRACER_VEC_H

#include <math.h>

struct vec3 {
	double x, y, z;
};

static inline struct vec3 v3(double x, double y, double z)
{
	struct vec3 v = { x, y, z };
	return v;
}

static inline struct vec3 v3_add(struct vec3 a, struct vec3 b)
{
	return v3(a.x + b.x, a.y + b.y, a.z + b.z);
}

static inline struct vec3 v3_sub(struct vec3 a, struct vec3 b)
{
	return v3(a.x - b.x, a.y - b.y, a.z - b.z);
}

static inline struct vec3 v3_scale(struct vec3 a, double s)
{
	return v3(a.x * s, a.y * s, a.z * s);
}

static inline double v3_dot(struct vec3 a, struct vec3 b)
{
	return a.x * b.x + a.y * b.y + a.z * b.z;
}

static inline struct vec3 v3_cross(struct vec3 a, struct vec3 b)
{
	return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
		  a.x * b.y - a.y * b.x);
}

static inline double v3_len(struct vec3 a)
{
	return sqrt(v3_dot(a, a));
}

static inline struct vec3 v3_norm(struct vec3 a)
{
	double l = v3_len(a);

	return l > 0.0 ? v3_scale(a, 1.0 / l) : a;
}

/* An orthonormal frame (s, t, n) around unit n (Duff et al. 2017,
 * "Building an Orthonormal Basis, Revisited", JCGT 6(1)). */
struct frame {
	struct vec3 s, t, n;
};

static inline struct frame frame_from_normal(struct vec3 n)
{
	struct frame f;
	double sign = copysign(1.0, n.z);
	double a = -1.0 / (sign + n.z);
	double b = n.x * n.y * a;

	f.s = v3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
	f.t = v3(b, sign + n.y * n.y * a, -n.y);
	f.n = n;
	return f;
}

static inline struct vec3 frame_to_local(const struct frame *f, struct vec3 w)
{
	return v3(v3_dot(w, f->s), v3_dot(w, f->t), v3_dot(w, f->n));
}

static inline struct vec3 frame_to_world(const struct frame *f, struct vec3 w)
{
	return v3_add(v3_add(v3_scale(f->s, w.x), v3_scale(f->t, w.y)),
		      v3_scale(f->n, w.z));
}

#endif /* TRACER_VEC_H */
