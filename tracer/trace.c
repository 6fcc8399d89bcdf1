/*
 * trace.c - a trace run: check the options, allocate the result, run the
 * worker threads over the batches, merge per-batch tallies in batch order
 * (bit-identical for any thread count), and the guided two-pass scheme.
 * The pass over a batch range and the pilot's guide are public
 * (batches.h) so that mpi/ can run the same trace spread over ranks.
 */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tracer/batches.h"
#include "tracer/cancel.h"
#include "tracer/guide.h"
#include "tracer/integrator.h"
#include "beam_screen.h"
#include "light.h"

void tracer_trace_defaults(struct tracer_trace_opts *o)
{
	memset(o, 0, sizeof(*o));
	o->n_paths = 100000;
	o->seed = 1;
	o->threads = 1;
	o->n_batches = 64;
	o->rr_depth = 2;
	o->rr_weight = 0.05;
	o->max_depth = 64;
	o->guide = 1;
}

static int check_opts(const struct tracer_scene *s,
		      const struct tracer_trace_opts *o,
		      struct stray_error *err)
{
	size_t j;

	if (!s->rt)
		return stray_error_set(err, STRAY_EINVAL, "scene",
				       "not committed");
	if (o->n_theta == 0)
		return stray_error_set(err, STRAY_EINVAL, "angles",
				       "list is empty");
	for (j = 0; j < o->n_theta; j++)
		if (!(o->theta_deg[j] >= 0.0 && o->theta_deg[j] <= 180.0))
			return stray_error_set_value(err, STRAY_EINVAL,
				"theta_deg", "must be in [0, 180]",
				o->theta_deg[j]);
	for (j = 0; o->beam_shift_z && j < o->n_theta; j++)
		if (!isfinite(o->beam_shift_z[j]))
			return stray_error_set_value(err, STRAY_EINVAL,
				"beam_shift_z", "must be finite",
				o->beam_shift_z[j]);
	for (j = 0; o->light_ratio && j < o->n_theta; j++)
		if (!(o->light_ratio[j] >= 0.0 && o->light_ratio[j] <= 64.0))
			return stray_error_set_value(err, STRAY_EINVAL,
				"light_ratio", "must be in [0, 64]",
				o->light_ratio[j]);
	if (o->n_batches < 2 || o->n_paths < (uint64_t)o->n_batches)
		return stray_error_set_value(err, STRAY_EINVAL, "rays",
			"need at least one path per batch (and 2 batches)",
			(double)o->n_paths);
	if (o->threads < 1 || o->threads > 256)
		return stray_error_set_value(err, STRAY_EINVAL, "threads",
					     "must be 1 to 256", o->threads);
	if (o->max_depth < 1 || o->max_depth > 1000 || o->rr_depth < 1 ||
	    !(o->rr_weight > 0.0))
		return stray_error_set(err, STRAY_EINVAL, "roulette",
				       "depths must be >= 1, weight > 0");
	if (o->map_n < 0 || o->map_n > 4096 ||
	    (o->map_n && o->map_theta_index >= o->n_theta))
		return stray_error_set_value(err, STRAY_EINVAL, "map",
			"size must be 0 to 4096 at a traced angle", o->map_n);
	if (o->focal && (o->focal->theta_index >= o->n_theta ||
			 tracer_focal_check(o->focal, err)))
		return stray_error_set_value(err, STRAY_EINVAL, "focal map",
			"needs a traced angle and a valid lens and size",
			(double)o->focal->theta_index);
	if (o->dump_paths > 1000000 || o->dump_paths > o->n_paths)
		return stray_error_set_value(err, STRAY_EINVAL, "dump",
			"at most 1e6 paths, and no more than traced",
			(double)o->dump_paths);
	return tracer_detector_check(&s->det, err);
}

/* The optional per-path dump and the detector map with its extent. */
static int alloc_extras(const struct tracer_scene *s,
			const struct tracer_trace_opts *o,
			struct tracer_result *r, double **batch_maps)
{
	size_t px = (size_t)o->map_n * (size_t)o->map_n;

	r->n_dump = o->dump_paths;
	if (r->n_dump) {
		r->dump = calloc(r->n_dump * TRACER_DUMP_DEPTH,
				 sizeof(*r->dump));
		r->dump_len = calloc(r->n_dump, sizeof(int));
		if (!r->dump || !r->dump_len)
			return STRAY_ENOMEM;
	}
	if (o->focal) {
		r->focal_slots = tracer_focal_slots(o->focal);
		r->focal = calloc(r->focal_slots, sizeof(double));
		r->focal_batch = calloc(r->focal_slots * (size_t)o->n_batches,
					sizeof(double));
		if (!r->focal || !r->focal_batch)
			return STRAY_ENOMEM;
	}
	if (!o->map_n)
		return STRAY_OK;
	r->map_n = o->map_n;
	r->map_theta_deg = o->theta_deg[o->map_theta_index];
	r->map_half_w_mm = s->det.shape == TRACER_DET_DISK ?
			   s->det.radius_mm : s->det.half_w_mm;
	r->map_half_h_mm = s->det.shape == TRACER_DET_DISK ?
			   s->det.radius_mm : s->det.half_h_mm;
	r->map = calloc(px, sizeof(double));
	*batch_maps = calloc(px * (size_t)o->n_batches, sizeof(double));
	return r->map && *batch_maps ? STRAY_OK : STRAY_ENOMEM;
}

/*
 * Batch maps (and focal sums) summed in batch order (bit-identical), the
 * detector map then turned into
 * irradiance over beam irradiance: sum / N * A_det / A_pixel.
 */
static void merge_maps(const struct tracer_scene *s, struct worker_ctx *w)
{
	struct tracer_result *r = w->res;
	size_t px = (size_t)r->map_n * r->map_n, i;
	double a_px = 4.0 * r->map_half_w_mm * r->map_half_h_mm / px;
	int b;

	/* focal cells: the mean of batch means, as tracer_result_power */
	for (b = 0; r->focal && b < r->n_batches; b++)	/* batch order */
		for (i = 0; i < r->focal_slots; i++)
			r->focal[i] += r->focal_batch[b * r->focal_slots + i] /
				       ((double)r->batch_paths[b] *
					r->n_batches);
	if (!r->map)
		return;
	for (b = 0; b < r->n_batches; b++)
		for (i = 0; i < px; i++)
			r->map[i] += w->batch_maps[(size_t)b * px + i];
	for (i = 0; i < px; i++)
		r->map[i] *= tracer_detector_area(&s->det) /
			     ((double)r->n_paths * a_px);
}

static int alloc_result(const struct tracer_trace_opts *o,
			struct tracer_result *r)
{
	size_t nb = (size_t)o->n_batches;

	memset(r, 0, sizeof(*r));
	r->n_theta = o->n_theta;
	r->n_batches = o->n_batches;
	r->n_paths = o->n_paths;
	r->batch_paths = calloc(nb, sizeof(uint64_t));
	r->power = calloc(nb * o->n_theta * TRACER_ORDERS, sizeof(double));
	r->energy = calloc(nb * TRACER_ENERGY_N, sizeof(double));
	r->theta_deg = malloc(o->n_theta * sizeof(double));
	if (r->theta_deg)
		memcpy(r->theta_deg, o->theta_deg,
		       o->n_theta * sizeof(double));
	return r->batch_paths && r->power && r->energy && r->theta_deg ?
	       STRAY_OK :
	       STRAY_ENOMEM;
}

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int run_workers(struct worker_ctx *w, int threads)
{
	pthread_t tid[256];
	int i, started = 0;

	for (i = 1; i < threads; i++) {
		if (pthread_create(&tid[i], NULL, tracer_worker, w) != 0)
			break;
		started = i;
	}
	tracer_worker(w);	/* the calling thread works too */
	for (i = 1; i <= started; i++)
		pthread_join(tid[i], NULL);
	return STRAY_OK;
}

/* Merge the batch path tables in batch order: bit-identical sums. */
static int merge_tables(struct worker_ctx *w)
{
	int b, rc = STRAY_OK;

	for (b = 0; b < w->res->n_batches; b++) {
		if (!rc)
			rc = tracer_paths_merge(&w->res->paths,
						&w->batch_tables[b]);
		tracer_paths_free(&w->batch_tables[b]);
	}
	return rc;
}

/* The beam centre at angle j: the scene's, or moved back along the
 * aperture normal by o->beam_shift_z[j] (the bits tracer_scene_spec_edit
 * gives for the same shift). */
static struct vec3 beam_center(const struct tracer_scene *s,
			       const struct tracer_trace_opts *o, size_t j)
{
	const struct tracer_beam *b = &s->beam;

	if (!o->beam_shift_z || o->beam_shift_z[j] == 0.0)
		return b->center;
	return v3_sub(b->center, v3_scale(b->normal, o->beam_shift_z[j]));
}

/* Batches [b0, b0 + nb) of a pass of o->n_paths paths; with a guide, or
 * filling pilot stats. */
static int run_pass(const struct tracer_scene *s,
		    const struct tracer_trace_opts *o, struct tracer_result *res,
		    const struct tracer_guide *guide, double *pilot_s2,
		    double *light_pilot, int b0, int nb,
		    struct stray_error *err)
{
	struct worker_ctx w;
	size_t j;
	int rc;

	memset(&w, 0, sizeof(w));
	w.s = s;
	w.o = o;
	w.res = res;
	w.guide = guide;
	w.pilot_s2 = pilot_s2;
	w.light_pilot = light_pilot;
	w.light_ratio = o->light_ratio;
	w.focal_frame = frame_from_normal(s->det.normal);
	w.next_batch = b0;
	w.end_batch = b0 + nb;
	w.n_run = nb;
	rc = alloc_result(o, res);
	if (!rc)
		rc = alloc_extras(s, o, res, &w.batch_maps);
	w.dir = malloc(o->n_theta * sizeof(*w.dir));
	w.dir_x = malloc(8 * o->n_theta * sizeof(*w.dir_x));
	w.batch_tables = calloc((size_t)o->n_batches, sizeof(*w.batch_tables));
	if (rc || !w.dir || !w.dir_x || !w.batch_tables) {
		rc = stray_error_set(err, STRAY_ENOMEM, "trace",
				     "out of memory");
		goto out_free;
	}
	w.dir_y = w.dir_x + o->n_theta;
	w.dir_z = w.dir_y + o->n_theta;
	w.beam_ok = w.dir_z + o->n_theta;
	w.direct_ok = w.beam_ok + o->n_theta;
	w.beam_cx = w.direct_ok + o->n_theta;
	w.beam_cy = w.beam_cx + o->n_theta;
	w.beam_cz = w.beam_cy + o->n_theta;
	for (j = 0; j < o->n_theta; j++) {
		struct vec3 d = tracer_source_dir(o->theta_deg[j]);
		struct vec3 c = beam_center(s, o, j);

		w.dir[j] = d;
		w.dir_x[j] = d.x;
		w.dir_y[j] = d.y;
		w.dir_z[j] = d.z;
		/* what tracer_beam_covers and the direct term test first,
		 * independent of the point */
		w.beam_ok[j] = v3_dot(d, s->beam.normal) > 0.0;
		w.direct_ok[j] = w.beam_ok[j] > 0.0 &&
				 v3_dot(d, s->det.normal) > 0.0 &&
				 tracer_detector_accepts(&s->det, d);
		w.beam_cx[j] = c.x;
		w.beam_cy[j] = c.y;
		w.beam_cz[j] = c.z;
	}
	tracer_screen_setup(&w);
	pthread_mutex_init(&w.lock, NULL);
	run_workers(&w, o->threads);
	pthread_mutex_destroy(&w.lock);
	merge_maps(s, &w);
	if (merge_tables(&w) || w.failed)
		rc = stray_error_set(err, STRAY_ENOMEM, "paths",
				     "out of memory recording paths");
	if (tracer_cancelled())	/* a part of the paths: no estimate */
		rc = stray_error_set(err, STRAY_EIO, "trace", "interrupted");
out_free:
	free(w.dir);
	free(w.dir_x);
	free(w.batch_tables);
	free(w.batch_maps);
	if (rc)
		tracer_result_free(res);
	return rc;
}

int tracer_pilot_wanted(const struct tracer_trace_opts *o)
{
	return o->guide && o->n_paths / 10 >= 1000;
}

/*
 * The pilot: a tenth of the paths (own random streams, 8 batches) scores
 * the guide's cells; its paths are not part of the estimate.
 */
void tracer_pilot_opts(const struct tracer_trace_opts *o,
		       struct tracer_trace_opts *po)
{
	*po = *o;
	po->n_batches = TRACER_PILOT_BATCHES;
	po->n_paths = o->n_paths / 10 > 200000 ? 200000 : o->n_paths / 10;
	po->seed = o->seed ^ 0x5DEECE66Dull;
	po->light_ratio = NULL;	/* the pilot measures B alone */
	po->record_paths = 0;
	po->dump_paths = 0;
	po->map_n = 0;
	po->focal = NULL;
}

int tracer_guide_from_pilot(struct tracer_guide *g,
			    const struct tracer_result *pilot,
			    const double *s2)
{
	struct tracer_guide_stats st = { pilot->n_theta, NULL };
	size_t per = TRACER_GUIDE_CELLS * pilot->n_theta, i, j;
	double *p = malloc(pilot->n_theta * sizeof(double));
	int b;

	st.s2 = calloc(per, sizeof(double));
	if (!p || !st.s2) {
		free(p);
		free(st.s2);
		return STRAY_ENOMEM;
	}
	for (b = 0; b < pilot->n_batches; b++)	/* batch order: bit-identical */
		for (i = 0; i < per; i++)
			st.s2[i] += s2[(size_t)b * per + i];
	for (j = 0; j < pilot->n_theta; j++) {
		double sg;

		tracer_result_power(pilot, j, -1, &p[j], &sg);
	}
	tracer_guide_build(g, &st, p);
	free(st.s2);
	free(p);
	return STRAY_OK;
}

/* The pilot: the guide, and with o->light_paths B's ratios light_q. */
static int build_guide(const struct tracer_scene *s,
		       const struct tracer_trace_opts *o,
		       struct tracer_guide *g, double *light_q,
		       struct stray_error *err)
{
	struct tracer_trace_opts po;
	struct tracer_result pr;
	double *s2, *lp = NULL;
	int rc;

	tracer_pilot_opts(o, &po);
	s2 = calloc(TRACER_GUIDE_CELLS * o->n_theta * po.n_batches,
		    sizeof(double));
	if (light_q)
		lp = calloc(TRACER_LIGHT_STATS * o->n_theta * po.n_batches,
			    sizeof(double));
	rc = s2 && (lp || !light_q) ?
	     run_pass(s, &po, &pr, NULL, s2, lp, 0, po.n_batches, err) :
	     stray_error_set(err, STRAY_ENOMEM, "guide", "out of memory");
	if (!rc) {
		if (tracer_guide_from_pilot(g, &pr, s2))
			rc = stray_error_set(err, STRAY_ENOMEM, "guide",
					     "out of memory");
		if (light_q)
			tracer_light_alloc(&pr, lp, light_q);
		tracer_result_free(&pr);
	}
	free(s2);
	free(lp);
	return rc;
}

int tracer_trace_check(const struct tracer_scene *s,
		       const struct tracer_trace_opts *o,
		       struct stray_error *err)
{
	return check_opts(s, o, err);
}

int tracer_trace_batches(const struct tracer_scene *s,
			 const struct tracer_trace_opts *o,
			 const struct tracer_guide *guide, int first_batch,
			 int n_batches, double *pilot_s2,
			 struct tracer_result *res, struct stray_error *err)
{
	return tracer_trace_batches_light(s, o, guide, first_batch, n_batches,
					  pilot_s2, NULL, res, err);
}

int tracer_trace_batches_light(const struct tracer_scene *s,
			       const struct tracer_trace_opts *o,
			       const struct tracer_guide *guide,
			       int first_batch, int n_batches,
			       double *pilot_s2, double *light_pilot,
			       struct tracer_result *res,
			       struct stray_error *err)
{
	double t0 = now_s();
	int rc = check_opts(s, o, err);

	if (rc)
		return rc;
	/* path records are kept: each batch's table is merged alone, so a
	 * piece's entries are that batch's sums (mpi/ merges them in order) */
	if (o->dump_paths || o->map_n || o->focal)
		return stray_error_set(err, STRAY_EINVAL, "trace",
			"dumps and maps need the whole trace");
	if (first_batch < 0 || n_batches < 1 ||
	    n_batches > o->n_batches - first_batch)
		return stray_error_set_value(err, STRAY_EINVAL, "batches",
			"range outside the trace's batches", first_batch);
	rc = run_pass(s, o, res, guide, pilot_s2, light_pilot, first_batch,
		      n_batches, err);
	if (!rc)
		res->seconds = now_s() - t0;
	return rc;
}

int tracer_trace(const struct tracer_scene *s,
		 const struct tracer_trace_opts *o, struct tracer_result *res,
		 struct stray_error *err)
{
	struct tracer_guide *g = NULL;
	struct tracer_trace_opts mo = *o;	/* the main pass's */
	double t0 = now_s(), *light_q = NULL;
	int rc = check_opts(s, o, err);

	if (rc)
		return rc;
	if (tracer_pilot_wanted(o)) {
		g = malloc(sizeof(*g));
		if (o->light_paths)	/* B sized by the pilot */
			mo.light_ratio = light_q = calloc(o->n_theta,
							  sizeof(double));
		rc = g && (light_q || !o->light_paths) ?
		     build_guide(s, o, g, light_q, err) :
		     stray_error_set(err, STRAY_ENOMEM, "guide", "out of memory");
	}
	if (!rc)
		rc = run_pass(s, &mo, res, g, NULL, NULL, 0, o->n_batches, err);
	if (!rc)
		res->seconds = now_s() - t0;
	free(g);
	free(light_q);
	return rc;
}
