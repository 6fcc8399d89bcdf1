/*
 * integrator.h - the Monte Carlo estimator of detector power.
 *
 * Adjoint (reciprocal) path tracing: paths start on the detector
 * (uniform point, cosine-weighted direction within the acceptance cone,
 * times the lens transmission at that incidence) and at every non-
 * specular scatter vertex connect to the collimated source of *every*
 * angle of the sweep (next-event estimation: a shadow ray toward the
 * source inside the beam).  One set of detector-side paths thus serves
 * the whole curve.  Direct light is the connection from the detector
 * point itself.  The detector point and the first two directions are
 * randomised QMC (R6 Kronecker, a random shift per batch); the first
 * direction is importance-sampled from a guide that a pilot tenth of the
 * paths builds (guide.h).  Russian roulette past rr_depth vertices; no
 * intensity floor.  Per-path counter-based random streams and fixed batches make a
 * seed give bit-identical results for any thread count.
 *
 * The estimate is of P(theta) / (E A_det): detector power over beam
 * irradiance times detector area; alpha(theta) = P(theta) / P(0)
 * (ref4-baffle.md, thesis §3.4).
 */
#ifndef TRACER_INTEGRATOR_H
#define TRACER_INTEGRATOR_H

#include <stddef.h>
#include <stdint.h>

#include "stray/error.h"
#include "tracer/detector.h"
#include "tracer/focal.h"
#include "tracer/paths.h"
#include "tracer/scene.h"

/* Scatter orders kept apart: direct, 1st, 2nd, 3rd and above (fig. 5.5). */
#define TRACER_ORDERS 4

enum tracer_light_weights { TRACER_LIGHT_BALANCE, TRACER_LIGHT_ONLY };

enum tracer_energy { TRACER_ABSORBED, TRACER_ESCAPED, TRACER_LOST,
		     TRACER_ENERGY_N };

struct tracer_trace_opts {
	const double *theta_deg;
	size_t n_theta;
	uint64_t n_paths;
	uint64_t seed;
	int threads;		/* >= 1 */
	int n_batches;		/* independent batches for sigma, >= 2 */
	int rr_depth;		/* vertices before Russian roulette starts */
	double rr_weight;	/* survival = min(1, throughput / rr_weight) */
	int max_depth;		/* hard bound on the loop (bias << sigma) */
	const struct tracer_lens *lens;	/* NULL: no lens */
	/* per angle, or NULL: that angle's beam centre moved back along
	 * the aperture normal by this many mm, as tracer_scene_spec's
	 * beam_shift_z moves it for every angle; so one pass traces several
	 * beam positions as repeated angles that share the paths and the
	 * shadow rays (the diagnosis's pivot-offset nodes); mpi/'s farm
	 * carries it to every rank. */
	const double *beam_shift_z;
	/* Strategy B, light-side single scatter (light.h), combined with
	 * the detector-side paths by multiple importance sampling:
	 * light_paths = 1 asks tracer_trace() to size it from its pilot
	 * (light_ratio is then its own); light_ratio, per angle or NULL,
	 * is that size: B samples per detector path at each angle (0:
	 * none), what tracer_trace_batches() uses as given.
	 * light_weights = TRACER_LIGHT_ONLY (tests) gives single scatter
	 * at those angles to B alone. */
	int light_paths;
	const double *light_ratio;
	int light_weights;
	int record_paths;	/* fill tracer_result.paths */
	int guide;		/* pilot-guided detector directions (guide.h);
				 * used from 10000 paths on (pilot: a tenth) */
	uint64_t dump_paths;	/* keep the vertices of paths 0..n-1 (fig. 5.6) */
	int map_n;		/* > 0: n x n detector irradiance map ... */
	size_t map_theta_index;	/* ... at this angle */
	/* non-NULL: focal-plane sums at focal->theta_index (focal.h) */
	const struct tracer_focal *focal;
	void (*progress)(void *user, double fraction);
	void *progress_user;
};

/* A vertex of a dumped path; vertex 0 is on the detector (group -1). */
#define TRACER_DUMP_DEPTH 16
struct tracer_vertex {
	float x, y, z;
	int group;
};

struct tracer_result {
	size_t n_theta;
	double *theta_deg;	/* [theta], a copy of the options' */
	int n_batches;
	uint64_t n_paths;
	uint64_t *batch_paths;	/* [batch] */
	double *power;		/* [batch][theta][order], sums of estimates */
	double *energy;		/* [batch][TRACER_ENERGY_N], adjoint emission 1 */
	uint64_t casts;		/* rtcIntersect1 + rtcOccluded1 calls */
	uint64_t connections;	/* shadow rays toward the source */
	double seconds;		/* wall time of the trace */
	struct tracer_path_table paths;	/* when record_paths */
	struct tracer_vertex *dump;	/* [path][TRACER_DUMP_DEPTH] */
	int *dump_len;			/* vertices kept per dumped path */
	uint64_t n_dump;
	double *map;		/* [row][col]: irradiance / beam irradiance */
	int map_n;
	double map_theta_deg;
	double map_half_w_mm, map_half_h_mm;	/* extent, detector frame */
	/* with opts.focal: per focal cell, the last slot outside the
	 * detector (focal.h), P_cell / (E A_det) estimated as
	 * tracer_result_power does (mean of batch means), and the per-batch
	 * sums of contributions */
	size_t focal_slots;
	double *focal;		/* [slot] */
	double *focal_batch;	/* [batch][slot] */
};

/* Defaults: 1 thread, 64 batches, roulette after 2 vertices, depth 64,
 * guided. */
void tracer_trace_defaults(struct tracer_trace_opts *o);

/* Trace; res is allocated here and freed with tracer_result_free. */
int tracer_trace(const struct tracer_scene *s,
		 const struct tracer_trace_opts *o, struct tracer_result *res,
		 struct stray_error *err);

void tracer_result_free(struct tracer_result *res);

/* Mean P/(E A_det) at angle j over all orders (order < 0) or one order,
 * and its standard error from the batches. */
void tracer_result_power(const struct tracer_result *res, size_t j,
			 int order, double *mean, double *sigma);

/*
 * alpha = P(j) / P(ref) for one order (order < 0: all), with the standard
 * error of the ratio from the batches (delta method: the spread of
 * P_b(j) - alpha P_b(ref) across batches, so shared paths' correlation
 * is kept).
 */
void tracer_result_alpha(const struct tracer_result *res, size_t j,
			 size_t ref, int order, double *alpha,
			 double *sigma);

#endif /* TRACER_INTEGRATOR_H */
