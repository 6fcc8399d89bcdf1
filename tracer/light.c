/*
 * light.c - strategy B: light-side single scatter combined with the
 * detector-side paths by multiple importance sampling (see light.h).
 */
#include <math.h>
#include <string.h>

#include "light.h"
#include "tracer/cancel.h"
#include "tracer/guide.h"
#include "tracer/rng.h"

uint64_t tracer_light_count(double q, uint64_t n_a)
{
	return q > 0.0 ? (uint64_t)ceil(q * (double)n_a) : 0;
}

/* A 64-bit mix (Steele, Lea and Flood 2014, SplitMix64's finaliser). */
static uint64_t mix64(uint64_t z)
{
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

/*
 * The first stream index of (angle j, batch b): keyed by the angle's
 * value and beam shift, not its place in the list, so a pass over a
 * subset of the angles (mpi/'s pieces) draws the same numbers.
 */
static uint64_t stream_base(const struct worker_ctx *w, size_t j, int b)
{
	double shift = w->o->beam_shift_z ? w->o->beam_shift_z[j] : 0.0;
	uint64_t t, s;

	memcpy(&t, &w->o->theta_deg[j], sizeof(t));
	memcpy(&s, &shift, sizeof(s));
	return mix64(mix64(t) ^ mix64(s + 0x9E3779B97F4A7C15ull) ^
		     mix64((uint64_t)b + 1));
}

/* The aperture disk's area times the beam's projection on it. */
static double beam_area(const struct worker_ctx *w, size_t j)
{
	const struct tracer_beam *b = &w->s->beam;

	return M_PI * b->radius_mm * b->radius_mm * v3_dot(w->dir[j],
							    b->normal);
}

double tracer_light_pdf_ratio(const struct worker_ctx *w, size_t j,
			      double cos_d, double f_a)
{
	return cos_d * f_a / beam_area(w, j);
}

/* n_B pB / (n_A pA) of one single-scatter path: the balance heuristic
 * (Veach 1997, ch. 9) weighs A by 1 / (1 + r) and B by r / (1 + r). */
static double mis_ratio(const struct worker_ctx *w, size_t j, uint64_t n_b,
			uint64_t n_a, double cos_d, double f_a)
{
	return (double)n_b / (double)n_a * tracer_light_pdf_ratio(w, j, cos_d,
								   f_a);
}

double tracer_light_weight_a(const struct worker_ctx *w, size_t j,
			     uint64_t n_a, double cos_d, double f_a)
{
	uint64_t n_b = tracer_light_count(w->light_ratio[j], n_a);

	if (n_b == 0)
		return 1.0;
	if (w->o->light_weights == TRACER_LIGHT_ONLY)
		return 0.0;
	return 1.0 / (1.0 + mis_ratio(w, j, n_b, n_a, cos_d, f_a));
}

/* One B sample: its estimate (0: none) and what its tallies need. */
struct light_sample {
	double e;		/* A_ap (d.n_ap) f cos_x cos_p / r^2 lens */
	double f_a;		/* proj g r^2 / (cos_p cos_x) */
	double cos_d, rho;
	struct vec3 p, w;	/* detector point, direction toward x */
	int group;
};

/* The guide weight g of a path leaving the detector along dir. */
static double guide_weight(const struct worker_ctx *w, struct vec3 dir)
{
	double u1, u2;

	if (!w->guide)
		return 1.0;
	tracer_detector_dir_inverse(&w->s->det, dir, &u1, &u2);
	return 1.0 / (TRACER_GUIDE_CELLS *
		      w->guide->p[tracer_guide_cell(u1, u2)]);
}

/*
 * Does the detector point p see x (n: x's normal on p's side)?  The shadow
 * ray between the two points, each moved off its surface as every ray of
 * the tracer is (tracer_offset_origin): then x is the first hit from p,
 * as the detector-side path that makes the same connection needs.
 */
static int sees(const struct tracer_scene *s, struct vec3 p, struct vec3 x,
		struct vec3 n)
{
	struct vec3 o = tracer_offset_origin(p, s->det.normal);
	struct vec3 v = v3_sub(tracer_offset_origin(x, n), o);
	double l = v3_len(v);

	return l > 0.0 && !tracer_scene_occluded(s, o, v3_scale(v, 1.0 / l), l);
}

/*
 * The lit point from aperture point a (the first hit against the beam),
 * accepted exactly when connect_vertex() would connect it to angle j:
 * non-specular, lit side, inside the beam, shadow ray unoccluded.
 */
static int lit_point(const struct worker_ctx *w, size_t j, struct vec3 a,
		     struct tracer_hit *h, struct light_out *out)
{
	const struct tracer_scene *s = w->s;
	const struct tracer_brdf *mat;
	struct tracer_beam beam = s->beam;
	struct vec3 d = w->dir[j];

	out->casts++;
	if (!tracer_scene_intersect(s, a, v3_scale(d, -1.0), h))
		return 0;
	mat = &s->material[h->group];
	if (!mat->ops || mat->rho <= 0.0 ||
	    (mat->ops->flags(mat) & TRACER_BRDF_SPECULAR) ||
	    v3_dot(d, h->ng) <= 0.0)
		return 0;
	beam.center = v3(w->beam_cx[j], w->beam_cy[j], w->beam_cz[j]);
	if (!tracer_beam_covers(&beam, d, h->p))
		return 0;
	out->casts++;
	out->connections++;
	return !tracer_scene_occluded(s, tracer_offset_origin(h->p, h->ng), d,
				      INFINITY);
}

static void sample(const struct worker_ctx *w, size_t j,
		   struct tracer_rng *rng, struct light_sample *ls,
		   struct light_out *out)
{
	const struct tracer_scene *s = w->s;
	const struct tracer_brdf *mat;
	struct frame fa = frame_from_normal(s->beam.normal), fx;
	struct tracer_hit h;
	struct vec3 a, d = w->dir[j], v;
	double u[4], x, y, r2, cos_p, cos_x, fv;
	int k;

	ls->e = 0.0;
	for (k = 0; k < 4; k++)	/* all four drawn: a fixed stream layout */
		u[k] = tracer_rng_uniform(rng);
	tracer_sample_disk(u[0], u[1], &x, &y);
	a = v3(w->beam_cx[j], w->beam_cy[j], w->beam_cz[j]);
	a = v3_add(a, v3_add(v3_scale(fa.s, x * s->beam.radius_mm),
			     v3_scale(fa.t, y * s->beam.radius_mm)));
	if (!lit_point(w, j, a, &h, out))
		return;
	ls->p = tracer_detector_sample_point(&s->det, u[2], u[3]);
	v = v3_sub(h.p, ls->p);
	r2 = v3_dot(v, v);
	ls->w = v3_scale(v, 1.0 / sqrt(r2));
	cos_x = -v3_dot(ls->w, h.ng);
	if (cos_x <= 0.0 || !tracer_detector_accepts(&s->det, ls->w))
		return;
	out->casts++;
	if (!sees(s, ls->p, h.p, h.ng))
		return;
	mat = &s->material[h.group];
	fx = frame_from_normal(h.ng);
	fv = mat->ops->eval(mat, frame_to_local(&fx, v3_scale(ls->w, -1.0)),
			    frame_to_local(&fx, d));
	if (fv <= 0.0)
		return;
	cos_p = v3_dot(ls->w, s->det.normal);
	ls->cos_d = v3_dot(d, h.ng);
	ls->f_a = tracer_detector_proj_solid_angle(&s->det) *
		  guide_weight(w, ls->w) * r2 / (cos_p * cos_x);
	ls->e = beam_area(w, j) * fv * cos_x * cos_p / r2;
	if (w->o->lens)
		ls->e *= tracer_lens_transmission(w->o->lens,
			acos(fmin(cos_p, 1.0)) * 180.0 / M_PI);
	ls->rho = mat->rho;
	ls->group = h.group;
}

/* B's weighted estimate into the batch's tallies (order 1), the map, the
 * focal cells and the path records, as connect_vertex() does for A. */
static void tally(struct worker_ctx *w, size_t j, const struct light_sample
		  *ls, double c, struct light_out *out)
{
	const struct tracer_trace_opts *o = w->o;
	long px;
	uint64_t key;

	out->acc[j * TRACER_ORDERS + 1] += c;
	if (out->map && j == o->map_theta_index &&
	    (px = tracer_map_pixel(w, ls->p)) >= 0)
		out->map[px] += c;
	if (out->focal && j == o->focal->theta_index)
		out->focal[tracer_focal_cell(o->focal, &w->focal_frame,
					     ls->w)] += c;
	if (!out->table)
		return;
	key = tracer_seq_pack(&ls->group, 1);
	if (tracer_paths_add(out->table, (uint32_t)j, key, c / ls->rho))
		out->failed = 1;
}

double tracer_light_grid_q(int k)
{
	return k == 0 ? 0.0 : ldexp(TRACER_LIGHT_RATIO_MAX, 1 - k);
}

/* The pilot: B alone, its statistics (pA/pB of the unguided pilot). */
static void pilot_angle(struct worker_ctx *w, int b, size_t j,
			struct light_out *out)
{
	double *st = w->light_pilot + ((size_t)b * w->o->n_theta + j) *
				      TRACER_LIGHT_STATS;
	uint64_t base = stream_base(w, j, b), k, c0 = out->casts;
	uint64_t n0 = out->connections;
	int g;

	for (k = 0; k < TRACER_LIGHT_PILOT; k++) {
		struct tracer_rng rng;
		struct light_sample ls;
		double rho;

		tracer_rng_init(&rng, w->o->seed ^ 0x4C49474854ull, base + k);
		sample(w, j, &rng, &ls, out);
		if (ls.e == 0.0)
			continue;
		st[1] += ls.e;
		rho = 1.0 / tracer_light_pdf_ratio(w, j, ls.cos_d, ls.f_a);
		for (g = 0; g < TRACER_LIGHT_GRID; g++) {
			double q = tracer_light_grid_q(g);

			st[3 + g] += ls.e * ls.e * (1.0 + q) / (rho + q);
		}
	}
	st[0] += TRACER_LIGHT_PILOT;
	st[2] += (double)(out->casts - c0);
	/* the pilot's casts and connections count A's paths alone: so a
	 * pilot piece's casts - connections are its paths' own casts,
	 * the same in every angle chunk (mpi/piece.c sums them once) */
	out->casts = c0;
	out->connections = n0;
}

void tracer_light_batch(struct worker_ctx *w, int b, uint64_t n_a,
			struct light_out *out)
{
	size_t j;

	for (j = 0; j < w->o->n_theta; j++) {
		uint64_t n_b, base, k;

		if (w->light_pilot) {
			pilot_angle(w, b, j, out);
			continue;
		}
		n_b = w->light_ratio ? tracer_light_count(w->light_ratio[j],
							  n_a) : 0;
		base = stream_base(w, j, b);
		for (k = 0; k < n_b; k++) {
			struct tracer_rng rng;
			struct light_sample ls;
			double wb;

			if ((k & 1023) == 0 && tracer_cancelled())
				return;
			tracer_rng_init(&rng, w->o->seed ^ 0x4C49474854ull,
					base + k);
			sample(w, j, &rng, &ls, out);
			if (ls.e == 0.0)
				continue;
			if (w->o->light_weights == TRACER_LIGHT_ONLY)
				wb = 1.0;
			else {
				double r = mis_ratio(w, j, n_b, n_a, ls.cos_d,
						     ls.f_a);

				wb = r / (1.0 + r);
			}
			tally(w, j, &ls, (double)n_a / (double)n_b * wb * ls.e,
			      out);
		}
	}
}
