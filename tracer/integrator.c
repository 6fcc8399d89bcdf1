/*
 * integrator.c - adjoint path tracing with next-event connections to the
 * collimated source at every angle of the sweep (see integrator.h).
 */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tracer/cancel.h"
#include "tracer/guide.h"
#include "tracer/integrator.h"
#include "tracer/rng.h"
#include "beam_screen.h"
#include "light.h"

/* Per-path state threaded through the vertex loop. */
struct path_state {
	double *acc;		/* this batch's [theta][order] */
	double *map;		/* this batch's irradiance map, or NULL */
	long pixel;		/* map pixel of the path's detector point */
	double *focal;		/* this batch's focal sums, or NULL */
	size_t focal_cell;	/* focal cell of the path's first direction */
	struct tracer_vertex *dump;	/* this path's dump slots, or NULL */
	int *dump_len;
	struct tracer_path_table *table;
	int seq[TRACER_SEQ_MAX];	/* groups, detector side first */
	uint64_t batch_first;	/* first path index of the batch */
	double shift[6];	/* the batch's random QMC shift */
	double u_first[2];	/* QMC numbers of the first BRDF sample */
	double *path_c;		/* pilot: this path's scattered c per angle */
	size_t *touched, n_touched;
	int cell;		/* pilot: guide cell of the path's direction */
	int failed;
	uint64_t n_a;		/* MIS with B (light.h): batch's paths, */
	struct vec3 det_p;	/* detector point, proj g / cos_p, and */
	double f_start, f_a;	/* proj g r^2 / (cos_p cos_x) at depth 1 */
	double rho_prod;
	uint64_t casts, connections;
};

/* Path record: contribution / prod rho under (angle, group sequence). */
static void record(struct path_state *ps, uint32_t j, int depth, double c)
{
	int g[TRACER_SEQ_MAX], i;
	int n = depth < TRACER_SEQ_MAX ? depth : TRACER_SEQ_MAX;
	uint64_t key;

	if (!ps->table || ps->rho_prod <= 0.0)
		return;
	/* the key lists groups from the source side to the detector */
	for (i = 0; i < n; i++)
		g[i] = ps->seq[n - 1 - i];
	key = tracer_seq_pack(g, n);
	if (depth > TRACER_SEQ_MAX)
		key |= TRACER_SEQ_TRUNCATED;
	if (tracer_paths_add(ps->table, j, key, c / ps->rho_prod))
		ps->failed = 1;
}

static void add_to_map(const struct worker_ctx *w, struct path_state *ps,
		       size_t j, double c)
{
	if (ps->map && ps->pixel >= 0 && j == w->o->map_theta_index)
		ps->map[ps->pixel] += c;
}

/* Focal-plane cell of light arriving from w, at the mapped angle only. */
static void add_to_focal(const struct worker_ctx *w, struct path_state *ps,
			 size_t j, double c, size_t cell)
{
	if (ps->focal && j == w->o->focal->theta_index)
		ps->focal[cell] += c;
}

long tracer_map_pixel(const struct worker_ctx *w, struct vec3 x)
{
	const struct tracer_result *r = w->res;
	struct frame f = frame_from_normal(w->s->det.normal);
	struct vec3 q = frame_to_local(&f, v3_sub(x, w->s->det.center));
	long col = (long)floor((q.x / r->map_half_w_mm + 1.0) * 0.5 * r->map_n);
	long row = (long)floor((q.y / r->map_half_h_mm + 1.0) * 0.5 * r->map_n);

	if (col < 0 || row < 0 || col >= r->map_n || row >= r->map_n)
		return -1;
	return row * r->map_n + col;
}

static void dump_vertex(struct path_state *ps, struct vec3 p, int group)
{
	if (ps->dump && *ps->dump_len < TRACER_DUMP_DEPTH) {
		struct tracer_vertex *v = &ps->dump[(*ps->dump_len)++];

		v->x = (float)p.x;
		v->y = (float)p.y;
		v->z = (float)p.z;
		v->group = group;
	}
}

/*
 * The shadow rays of one point (the detector point or a scatter vertex) to
 * the angles of the sweep: the angles are screened a block at a time
 * (beam_screen.c), those it cannot decide get the exact test, and the
 * candidates are traced as packets (tracer_scene_occluded_fan) and
 * tallied in angle order: the same rays, the same sums, the same bits.
 */
#define BLOCK TRACER_SCREEN_BLOCK
#define FAN (2 * BLOCK)		/* candidates gathered before tracing */

/* Lit from p by angle j, given its screen class (keep). */
static bool lit(const struct worker_ctx *w, double keep, size_t j,
		struct vec3 d, struct vec3 p)
{
	return keep == TRACER_SCREEN_YES ||
	       (keep == TRACER_SCREEN_ASK && tracer_screen_covers(w, j, d, p));
}

/*
 * The shadow rays of a fan's n candidates from o, counted, occ[k] for
 * candidate k.  With beam shifts (an angle repeated with other beam
 * centres, laid out side by side) a run of equal directions is one ray.
 */
static void trace_fan(const struct worker_ctx *w, struct path_state *ps,
		      struct vec3 o, const struct vec3 *dirs, size_t n,
		      unsigned char *occ)
{
	struct vec3 u_dirs[FAN];
	unsigned char u_occ[FAN];
	size_t ray_of[FAN], k, n_u = 0;

	if (!w->o->beam_shift_z || n == 0) {
		ps->casts += n;
		ps->connections += n;
		tracer_scene_occluded_fan(w->s, o, dirs, n, occ);
		return;
	}
	for (k = 0; k < n; k++) {
		const struct vec3 *d = &dirs[k], *e = &dirs[k ? k - 1 : 0];

		if (k == 0 || e->x != d->x || e->y != d->y || e->z != d->z)
			u_dirs[n_u++] = *d;
		ray_of[k] = n_u - 1;
	}
	ps->casts += n_u;
	ps->connections += n_u;
	tracer_scene_occluded_fan(w->s, o, u_dirs, n_u, u_occ);
	for (k = 0; k < n; k++)
		occ[k] = u_occ[ray_of[k]];
}

/* Direct light: the detector point connected to each source angle. */
static void connect_direct(struct worker_ctx *w, struct path_state *ps,
			   struct vec3 x)
{
	const struct tracer_scene *s = w->s;
	struct vec3 o = tracer_offset_origin(x, s->det.normal), dirs[FAN];
	double cs[FAN];
	size_t jj[FAN], j0, n = 0, k, lo, nt;
	unsigned char occ[FAN];
	double keep[BLOCK];

	tracer_screen_range(w, x, &lo, &nt);
	for (j0 = lo; j0 < nt; j0 += BLOCK) {
		size_t m = nt - j0 < BLOCK ? nt - j0 : BLOCK;

		/* cheap culling first: no ray for these */
		tracer_screen(w, w->direct_ok, j0, m, x, NULL, keep);
		for (k = 0; k < m; k++) {
			size_t j = j0 + k;
			struct vec3 d = w->dir[j];

			if (!lit(w, keep[k], j, d, x))
				continue;
			jj[n] = j;
			cs[n] = v3_dot(d, s->det.normal);
			dirs[n++] = d;
		}
		if (n < BLOCK && j0 + m < nt)
			continue;
		trace_fan(w, ps, o, dirs, n, occ);
		for (k = 0; k < n; k++) {
			size_t jk = jj[k];
			double c = cs[k];

			if (occ[k])
				continue;
			if (w->o->lens)	/* else 1: no acos per ray */
				c *= tracer_lens_transmission(w->o->lens,
					acos(fmin(c, 1.0)) * 180.0 / M_PI);
			ps->acc[jk * TRACER_ORDERS] += c;
			add_to_map(w, ps, jk, c);
			if (ps->focal && jk == w->o->focal->theta_index)
				/* direct light arrives from the source */
				add_to_focal(w, ps, jk, c, tracer_focal_cell(
					w->o->focal, &w->focal_frame, dirs[k]));
		}
		n = 0;
	}
}

/*
 * Next-event connection at a scatter vertex: T f(wo, d) cos(n, d) V(x, d),
 * the collimated source being E delta(w - d) (adjoint transport by
 * reciprocity: Veach 1997, PhD thesis, Stanford, ch. 3-4).
 */
static void connect_vertex(struct worker_ctx *w, struct path_state *ps,
			   const struct tracer_hit *h, const struct frame *f,
			   const struct tracer_brdf *mat, struct vec3 wo,
			   double T, int depth)
{
	struct vec3 o = tracer_offset_origin(h->p, h->ng), dirs[FAN];
	int order = depth < TRACER_ORDERS - 1 ? depth : TRACER_ORDERS - 1;
	double cs[FAN], fv_last = 0.0;
	size_t jj[FAN], j0, n = 0, k, lo, nt;
	unsigned char occ[FAN];
	double keep[BLOCK];
	struct vec3 d_last = v3(0.0, 0.0, 0.0);	/* not a direction */

	tracer_screen_range(w, h->p, &lo, &nt);	/* the angles that may light it */
	for (j0 = lo; j0 < nt; j0 += BLOCK) {
		size_t m = nt - j0 < BLOCK ? nt - j0 : BLOCK;

		/* cheap culling first: below the surface, outside the
		 * aperture seen from the vertex, or a zero BRDF: no ray */
		tracer_screen(w, w->beam_ok, j0, m, h->p, &h->ng, keep);
		for (k = 0; k < m; k++) {
			size_t j = j0 + k;
			struct vec3 d = w->dir[j];
			double cos_d, fv;

			if (keep[k] == TRACER_SCREEN_NO)
				continue;
			cos_d = v3_dot(d, h->ng);
			if (cos_d <= 0.0 || !lit(w, keep[k], j, d, h->p))
				continue;
			/* a direction repeated with other beam centres
			 * (opts.beam_shift_z) side by side: one evaluation */
			if (d.x != d_last.x || d.y != d_last.y ||
			    d.z != d_last.z) {
				fv_last = mat->ops->eval(mat, wo,
							 frame_to_local(f, d));
				d_last = d;
			}
			fv = fv_last;
			if (fv <= 0.0)
				continue;
			jj[n] = j;
			cs[n] = T * fv * cos_d;
			if (depth == 1 && w->light_ratio)	/* MIS with B */
				cs[n] *= tracer_light_weight_a(w, j, ps->n_a,
						cos_d, ps->f_a);
			dirs[n++] = d;
		}
		if (n < BLOCK && j0 + m < nt)
			continue;
		trace_fan(w, ps, o, dirs, n, occ);
		for (k = 0; k < n; k++) {
			size_t jk = jj[k];
			double c = cs[k];

			if (occ[k])
				continue;
			ps->acc[jk * TRACER_ORDERS + order] += c;
			add_to_map(w, ps, jk, c);
			add_to_focal(w, ps, jk, c, ps->focal_cell);
			if (ps->path_c) {	/* c = 0 (a lens table of zeros):
						 * not touched, or listed twice */
				if (ps->path_c[jk] == 0.0 && c != 0.0)
					ps->touched[ps->n_touched++] = jk;
				ps->path_c[jk] += c;
			}
			record(ps, (uint32_t)jk, depth, c);
		}
		n = 0;
	}
}

/*
 * The first six dimensions (detector point, direction, first bounce) of a
 * path come from a randomised quasi-Monte Carlo set: the R6 Kronecker sequence
 * (Roberts 2018, "The unreasonable effectiveness of quasirandom
 * sequences", extremelearning.com.au) with a random shift per batch
 * (Cranley and Patterson 1976, SIAM J. Numer. Anal. 13(6)).  Batches stay
 * independent, so their spread is still an honest standard error; within
 * one the points cover the detector's phase space evenly.
 */
static void qmc_point(const struct path_state *ps, uint64_t index,
		      double u[6])
{
	/* 1 / phi_6^k, phi_6 the real root of x^7 = x + 1 */
	static const double g[6] = {
		0.8986537126286992, 0.8075784952213447, 0.7257334129697598,
		0.6521830259439716, 0.5860866975779693, 0.5266889867007358
	};
	double i = (double)(index - ps->batch_first);
	int k;

	for (k = 0; k < 6; k++) {
		double v = ps->shift[k] + i * g[k];

		u[k] = v - floor(v);
	}
}

/*
 * The path's start on the detector: a QMC point (its direct light goes
 * straight to the tally) and a cosine-weighted direction; returns the
 * starting throughput, pi sin^2(cone) times the lens transmission at
 * that incidence times the guide's weight (also the start of the analog
 * energy weight, whose expectation stays 1).
 */
static double start_path(struct worker_ctx *w, struct path_state *ps,
			 uint64_t index, struct vec3 *o, struct vec3 *dir,
			 double *guide_weight)
{
	const struct tracer_scene *s = w->s;
	struct vec3 x;
	double u[6], proj, c, g;

	qmc_point(ps, index, u);
	ps->u_first[0] = u[4];
	ps->u_first[1] = u[5];
	x = tracer_detector_sample_point(&s->det, u[0], u[1]);
	ps->pixel = ps->map ? tracer_map_pixel(w, x) : -1;
	ps->dump = NULL;
	if (index < w->res->n_dump) {
		ps->dump = w->res->dump + index * TRACER_DUMP_DEPTH;
		ps->dump_len = &w->res->dump_len[index];
	}
	dump_vertex(ps, x, -1);
	connect_direct(w, ps, x);
	ps->cell = tracer_guide_cell(u[2], u[3]);
	g = w->guide ? tracer_guide_sample(w->guide, &u[2], &u[3]) : 1.0;
	*guide_weight = g;
	*dir = tracer_detector_sample_dir(&s->det, u[2], u[3], &proj);
	/* scattered light reaches the pupil along the first direction */
	if (ps->focal)
		ps->focal_cell = tracer_focal_cell(w->o->focal,
						   &w->focal_frame, *dir);
	*o = tracer_offset_origin(x, s->det.normal);
	ps->det_p = x;
	ps->f_start = g * proj / v3_dot(*dir, s->det.normal);
	if (!w->o->lens)	/* transmission 1 */
		return g * proj;
	c = fmin(1.0, v3_dot(*dir, s->det.normal));
	return g * proj * tracer_lens_transmission(w->o->lens,
						   acos(c) * 180.0 / M_PI);
}

/* Russian roulette past rr_depth: unbiased, no hard intensity floor. */
static int survives(const struct tracer_trace_opts *op, struct tracer_rng *rng,
		    int depth, double *T, double *Te)
{
	double q;

	if (depth < op->rr_depth)
		return 1;
	q = fmin(1.0, *Te / op->rr_weight);
	if (tracer_rng_uniform(rng) >= q)
		return 0;
	*T /= q;
	*Te /= q;
	return 1;
}

/* One adjoint path from the detector; energy bookkeeping into en[]. */
static void trace_path(struct worker_ctx *w, struct path_state *ps,
		       uint64_t index, double *en)
{
	const struct tracer_scene *s = w->s;
	struct tracer_rng rng;
	struct vec3 dir, o;
	double Te, T = start_path(w, ps, index, &o, &dir, &Te);
	int depth;

	tracer_rng_init(&rng, w->o->seed, index);
	ps->rho_prod = 1.0;
	for (depth = 1; depth <= w->o->max_depth; depth++) {
		const struct tracer_brdf *mat;
		struct tracer_brdf_sample bs;
		struct tracer_hit h;
		struct frame f;
		struct vec3 wo;
		double u1, u2;

		ps->casts++;
		if (!tracer_scene_intersect(s, o, dir, &h)) {
			en[TRACER_ESCAPED] += Te;
			return;
		}
		dump_vertex(ps, h.p, h.group);
		mat = &s->material[h.group];
		if (!mat->ops || mat->rho <= 0.0) {
			en[TRACER_ABSORBED] += Te;
			return;
		}
		if (depth <= TRACER_SEQ_MAX)
			ps->seq[depth - 1] = h.group;
		if (depth == 1 && w->light_ratio)	/* r^2 / cos_x */
			ps->f_a = ps->f_start * v3_dot(v3_sub(h.p, ps->det_p),
				  v3_sub(h.p, ps->det_p)) / -v3_dot(dir, h.ng);
		ps->rho_prod *= mat->rho;
		f = frame_from_normal(h.ng);
		wo = frame_to_local(&f, v3_scale(dir, -1.0));
		if (!(mat->ops->flags(mat) & TRACER_BRDF_SPECULAR))
			connect_vertex(w, ps, &h, &f, mat, wo, T, depth);
		/* Sample the BRDF to continue the path (QMC the first time). */
		u1 = depth == 1 ? ps->u_first[0] : tracer_rng_uniform(&rng);
		u2 = depth == 1 ? ps->u_first[1] : tracer_rng_uniform(&rng);
		if (!mat->ops->sample(mat, wo, u1, u2, &bs) || bs.weight <= 0.0) {
			en[TRACER_ABSORBED] += Te;
			return;
		}
		en[TRACER_ABSORBED] += Te * (1.0 - bs.weight);
		T *= bs.weight;
		Te *= bs.weight;
		if (!survives(w->o, &rng, depth, &T, &Te))
			return;
		dir = frame_to_world(&f, bs.wi);
		o = tracer_offset_origin(h.p, h.ng);
	}
	en[TRACER_LOST] += Te;
}

uint64_t tracer_batch_start(const struct tracer_result *r, int b)
{
	return r->n_paths * (uint64_t)b / (uint64_t)r->n_batches;
}

/* Pilot: the path's squared contributions into its cell's tallies. */
static void pilot_flush(struct worker_ctx *w, struct path_state *ps, int b)
{
	size_t n = w->res->n_theta, k;
	double *s2 = w->pilot_s2 + ((size_t)b * TRACER_GUIDE_CELLS +
				    (size_t)ps->cell) * n;

	for (k = 0; k < ps->n_touched; k++) {
		size_t j = ps->touched[k];

		s2[j] += ps->path_c[j] * ps->path_c[j];
		ps->path_c[j] = 0.0;
	}
	ps->n_touched = 0;
}

static void run_batch(struct worker_ctx *w, int b, uint64_t *casts,
		      uint64_t *conn)
{
	struct tracer_result *r = w->res;
	struct path_state ps;
	struct tracer_rng rng;
	uint64_t i, end = tracer_batch_start(r, b + 1);
	int k;

	memset(&ps, 0, sizeof(ps));
	ps.acc = r->power + (size_t)b * r->n_theta * TRACER_ORDERS;
	ps.table = w->o->record_paths ? &w->batch_tables[b] : NULL;
	ps.batch_first = tracer_batch_start(r, b);
	ps.n_a = end - ps.batch_first;
	ps.map = r->map ? w->batch_maps + (size_t)b * r->map_n * r->map_n :
		 NULL;
	ps.focal = r->focal_batch ? r->focal_batch + (size_t)b * r->focal_slots
				  : NULL;
	/* the shift's stream lies beyond every path index */
	tracer_rng_init(&rng, w->o->seed, UINT64_MAX - (uint64_t)b);
	for (k = 0; k < 6; k++)
		ps.shift[k] = tracer_rng_uniform(&rng);
	if (w->pilot_s2) {
		ps.path_c = calloc(r->n_theta, sizeof(double));
		ps.touched = malloc(r->n_theta * sizeof(size_t));
		if (!ps.path_c || !ps.touched)
			w->failed = 1;
	}
	for (i = tracer_batch_start(r, b); i < end; i++) {
		/* a cancelled trace (tracer/cancel.h) fails: stop soon */
		if ((i & 1023) == 0 && tracer_cancelled())
			break;
		trace_path(w, &ps, i, r->energy + (size_t)b * TRACER_ENERGY_N);
		if (ps.path_c && ps.touched)
			pilot_flush(w, &ps, b);
	}
	free(ps.path_c);
	free(ps.touched);
	r->batch_paths[b] = end - tracer_batch_start(r, b);
	if (w->light_ratio || w->light_pilot) {
		struct light_out lo = { .acc = ps.acc, .map = ps.map,
					.focal = ps.focal, .table = ps.table };

		tracer_light_batch(w, b, r->batch_paths[b], &lo);
		ps.casts += lo.casts;
		ps.connections += lo.connections;
		ps.failed |= lo.failed;
	}
	*casts += ps.casts;
	if (ps.failed)
		w->failed = 1;
	*conn += ps.connections;
}

void *tracer_worker(void *arg)
{
	struct worker_ctx *w = arg;
	uint64_t casts = 0, conn = 0;

	for (;;) {
		int b;

		pthread_mutex_lock(&w->lock);
		b = w->next_batch < w->end_batch && !tracer_cancelled() ?
		    w->next_batch++ : -1;
		pthread_mutex_unlock(&w->lock);
		if (b < 0)
			break;
		run_batch(w, b, &casts, &conn);
		pthread_mutex_lock(&w->lock);
		w->done_batches++;
		if (w->o->progress)
			w->o->progress(w->o->progress_user,
				       (double)w->done_batches / w->n_run);
		pthread_mutex_unlock(&w->lock);
	}
	pthread_mutex_lock(&w->lock);
	w->res->casts += casts;
	w->res->connections += conn;
	pthread_mutex_unlock(&w->lock);
	return NULL;
}
