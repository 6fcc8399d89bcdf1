/*
 * frames_job.c - a run of `stray frames` as one library call
 * (frames_job.h): detector frames rendered for a source at theta (eq. 2.3
 * with k_px, stars by eq. 2.2 and 2.12, camera noise), run through two
 * star detectors, false stars counted and set against the FDR model
 * (eq. 2.18) and its extension (stray/fdr_field.h); the first frames
 * kept as a sweep folder and a PNG when asked.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "frames/focal_map_io.h"
#include "frames/frames_io.h"
#include "frames/frames_job.h"
#include "frames/frames_mapterm.h"
#include "frames/frames_sat.h"
#include "frames/frames_sky.h"
#include "frames/image_cv.h"
#include "stray/aem.h"
#include "stray/catalogue.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sensor_geom.h"
#include "tracer/cancel.h"

/* Solid angle of the rendered frame, through the ideal lens the focal
 * maps use (stray_sensor_pixel_deg). */
static double frames_fov_deg2(const struct stray_sensor *s, int cols,
			      int rows)
{
	double px_deg = stray_sensor_pixel_deg(s);

	return cols * px_deg * rows * px_deg;
}

void frames_opts_init(struct frames_opts *o)
{
	static const struct frames_opts defaults = {
		.frames = 1, .seed = 1, .save = 3, .mag_max = 10.0,
		.epoch = 2000.0
	};

	*o = defaults;
}

static int close_store(struct frames_job *st, int ok,
		       struct stray_error *err);

static void state_free(struct frames_job *st)
{
	close_store(st, 0, NULL);	/* a failed run leaves no folder */
	free(st->det_rows);
	free(st->weight);
	free(st->expect);
	free(st->tiles);
	free(st->dn);
	free(st->stars);
	free(st->det);
	free(st->ev[0].tile_sum);
	free(st->ev[0].fx);
	free(st->ev[0].fy);
	free(st->ev[1].fx);
	free(st->ev[1].fy);
}

/* alpha from the curve or the option; the window; the buffers. */
static int setup_frame(struct frames_job *st, struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s->sensor;
	size_t n;
	int i, tx, ty;

	if (st->a.curve) {
		struct stray_curve c;
		struct stray_curve_view v;
		int rc = stray_curve_load(st->a.curve, &c, err);

		if (rc != STRAY_OK)
			return rc;
		v = stray_curve_view_of(&c);
		st->alpha = stray_curve_alpha_at(&v, st->a.theta_deg);
		stray_curve_free(&c);
	} else {
		st->alpha = st->a.alpha;
	}
	st->k_px = fdr_setup_k_px(st->s);
	st->cols = st->a.window > 0 ? (int)st->a.window : (int)sn->pixels_x;
	st->rows = st->a.window > 0 ? (int)st->a.window : (int)sn->pixels_y;
	if (st->cols > sn->pixels_x || st->rows > sn->pixels_y)
		return stray_error_set_value(err, STRAY_EINVAL, "window",
			"is larger than the detector", st->a.window);
	st->col0 = ((int)sn->pixels_x - st->cols) / 2;
	st->row0 = ((int)sn->pixels_y - st->rows) / 2;
	n = (size_t)st->cols * st->rows;
	frames_detect_tiles(st->cols, st->rows, 128, &tx, &ty);
	st->expect = malloc(n * sizeof(float));
	st->dn = malloc(n * sizeof(uint16_t));
	st->stars = malloc(FRAMES_MAX_STARS * sizeof(*st->stars));
	st->det = malloc(2 * FRAMES_MAX_DET * sizeof(*st->det));
	st->tiles = malloc((size_t)tx * ty * sizeof(float));
	st->ev[0].tile_sum = calloc((size_t)tx * ty, sizeof(double));
	for (i = 0; i < 2; i++) {
		st->ev[i].tiles_x = tx;
		st->ev[i].tiles_y = ty;
		st->ev[i].max_f = FRAMES_MAX_FALSE_POS;
		st->ev[i].fx = malloc(FRAMES_MAX_FALSE_POS * sizeof(float));
		st->ev[i].fy = malloc(FRAMES_MAX_FALSE_POS * sizeof(float));
		st->out[i].det = st->det + i * FRAMES_MAX_DET;
		st->out[i].max = FRAMES_MAX_DET;
	}
	st->ev[1].tile_sum = st->ev[0].tile_sum;
	if (!st->expect || !st->dn || !st->stars || !st->det || !st->tiles ||
	    !st->ev[0].tile_sum || !st->ev[0].fx || !st->ev[0].fy ||
	    !st->ev[1].fx || !st->ev[1].fy)
		return stray_error_set(err, STRAY_ENOMEM, "frame", "no memory");
	return STRAY_OK;
}

/* The map (if any): weights over the window (divided by the map's mean,
 * then by their own mean over the window), the regions. */
static int setup_map(struct frames_job *st, struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s->sensor;
	struct focal_map_file fm;
	size_t i, n = (size_t)st->cols * st->rows;
	double sum = 0.0;
	int rc;

	st->wmean = 1.0;
	if (!st->a.map)
		return STRAY_OK;
	st->weight = malloc(n * sizeof(float));
	if (!st->weight)
		return stray_error_set(err, STRAY_ENOMEM, "map", "no memory");
	rc = focal_map_load(st->a.map, &fm, err);
	if (rc != STRAY_OK)
		return rc;
	focal_map_resample(&fm, (int)sn->pixels_x, (int)sn->pixels_y,
			   st->col0, st->row0, st->cols, st->rows,
			   fm.cell_mean, st->weight);
	focal_map_file_free(&fm);
	for (i = 0; i < n; i++)
		sum += st->weight[i];
	st->wmean = sum / n;
	if (!(st->wmean > 0.0))
		return stray_error_at(err, STRAY_EINVAL, st->a.map, 0, "window",
				      "no light falls on the rendered window");
	for (i = 0; i < n; i++)
		st->weight[i] = (float)(st->weight[i] / st->wmean);
	frames_map_regions(st->weight, n, &st->map);
	return STRAY_OK;
}

static int setup_model(struct frames_job *st, struct stray_error *err)
{
	int rc = frames_model_init(&st->fm, &st->s->sensor, st->s->flux.sun,
				   st->s->flux.drs, st->k_px,
				   st->alpha * st->wmean, st->cols, st->rows,
				   st->a.map ? &st->map : NULL, err);

	if (rc == STRAY_OK)
		rc = frames_model_rates(&st->fm, &st->rates, err);
	if (rc == STRAY_OK)
		rc = frames_alpha_required(&st->fm, &st->s->sensor, st->k_px,
					   st->s->rate, &st->req, err);
	frames_detect_cfg_init(&st->dc, &st->fm, &st->s->sensor);
	if (rc == STRAY_OK)
		rc = frames_lost_init(&st->lost, &st->fm, err);
	if (rc == STRAY_OK && st->weight) {	/* the map's structure */
		int d;

		st->resid_rel = frames_map_resid_rel(st->weight, st->cols,
						     st->rows, 128);
		st->flat[0] = st->rates.sliding;
		st->flat[1] = st->rates.clusters;
		rc = frames_mapterm_rates(&st->fm, st->resid_rel,
					  &st->rates.sliding,
					  &st->rates.clusters, err);
		for (d = 0; d < 2; d++)
			st->lost.det[d].bg_resid_rel = st->resid_rel;
	}
	if (rc == STRAY_OK)	/* white frames: refuse, not "agree" */
		rc = frames_saturation(&st->fm, st->weight,
			(size_t)st->cols * st->rows, st->alpha, &st->clip_frac,
			err);
	return rc;
}

static void frame_cfg(const struct frames_job *st, struct stray_frame_cfg *c)
{
	const struct stray_sensor *sn = &st->s->sensor;

	stray_frame_cfg_defaults(c, st->cols, st->rows);
	c->col0 = st->col0;
	c->row0 = st->row0;
	c->stray_e = st->fm.stray_e;	/* eq. 2.3 with k_px (and the map) */
	c->weight = st->weight;
	c->dark_e = sn->dark_current_e_s * sn->t_exp_s;
	c->read_noise_e = sn->read_noise_e;
	c->psf_sigma_px = st->dc.window_radius_px * STRAY_FRAMES_PSF_PER_RADIUS;
}

/* --out-dir: a sweep folder (stray/sweep_store.h) filled as a temporary
 * and renamed into place when the whole run succeeds (stray/file.h). */
static int open_store(struct frames_job *st, struct stray_error *err)
{
	int i, rc;

	if (!st->a.out_dir)
		return STRAY_OK;
	st->det_rows = malloc((size_t)st->rows * sizeof(uint16_t));
	if (!st->det_rows)
		return stray_error_set(err, STRAY_ENOMEM, "frame", "no memory");
	for (i = 0; i < st->rows; i++)
		st->det_rows[i] = (uint16_t)(st->row0 + i);
	if ((rc = stray_dir_open_atomic(&st->dir, st->a.out_dir, err)))
		return rc;
	st->dir_open = 1;
	rc = stray_sweep_store_open(&st->mf, st->dir.tmp, 0, err);
	st->store_open = rc == STRAY_OK;
	return rc;
}

/* Close the store; rename the folder into place when ok, else remove it. */
static int close_store(struct frames_job *st, int ok,
		       struct stray_error *err)
{
	if (st->store_open)
		stray_sweep_manifest_free(&st->mf);	/* the lock */
	st->store_open = 0;
	if (!st->dir_open)
		return STRAY_OK;
	st->dir_open = 0;
	if (ok)
		return stray_dir_commit(&st->dir, err);
	stray_dir_abort(&st->dir);
	return STRAY_OK;
}

/* One rendered frame as a FULL lab frame with the renderer's keywords. */
static int save_frame(struct frames_job *st, int i, size_t n_stars,
		      struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s->sensor;
	struct stray_sweep_key k[] = {
		{ "ALPHA", STRAY_SWEEP_KEY_DOUBLE, st->alpha, 0, NULL,
		  "system attenuation" },
		{ "KPX", STRAY_SWEEP_KEY_DOUBLE, st->k_px, 0, NULL,
		  "k_px = A_cs/(n_px A_px)" },
		{ "NORM", STRAY_SWEEP_KEY_STRING, 0.0, 0,
		  stray_normalisation_name(st->s->normalisation),
		  "normalisation of eq. 2.3" },
		{ "STRAYE", STRAY_SWEEP_KEY_DOUBLE, st->fm.stray_e, 0, NULL,
		  "[e-] mean stray per pixel" },
		{ "STARSRC", STRAY_SWEEP_KEY_STRING, 0.0, 0,
		  st->a.catalogue ? "real catalogue (--catalogue)" :
		  st->a.has_att ? "synthetic catalogue" : "synthetic",
		  st->a.has_att ? "stray/catalogue.h, --attitude"
				: "star field: no catalogue" },
		{ "NSTARS", STRAY_SWEEP_KEY_LONG, 0.0, (long)n_stars, NULL,
		  "stars rendered" },
	};
	struct stray_sweep_frame f;
	struct stray_sweep_image im;

	memset(&f, 0, sizeof(f));
	f.type = STRAY_SWEEP_FULL;		/* rendered: source on */
	f.angle_deg = st->a.has_theta ? st->a.theta_deg : 0.0;	/* --alpha */
	f.exptime_s = sn->t_exp_s;
	f.ndtrans = 1.0;			/* no ND filter */
	f.seqnum = i;
	f.sat_dn = STRAY_FRAMES_SAT_DN;
	f.full_frame = st->rows == (int)sn->pixels_y;
	f.instrument = "stray frames";
	f.extra = k;
	f.n_extra = sizeof(k) / sizeof(k[0]);
	im.n_rows = (size_t)st->rows;
	im.n_cols = (size_t)st->cols;
	im.col0 = st->col0;
	im.rows = st->det_rows;
	im.px = st->dn;
	return stray_sweep_store_append(&st->mf, &f, &im, err);
}

/* The first frame in e- as a false-colour PNG (the expectation buffer is
 * free once the frame is sampled). */
static int save_png(struct frames_job *st, struct stray_error *err)
{
	size_t i, n = (size_t)st->cols * st->rows;
	char msg[256];

	for (i = 0; i < n; i++)
		st->expect[i] = (float)((st->dn[i] - STRAY_FRAMES_BIAS_DN) *
					STRAY_FRAMES_GAIN_E_PER_DN);
	if (image_cv_false_colour(st->a.png, st->expect, (size_t)st->rows,
				  (size_t)st->cols, 1, 0, msg, sizeof(msg))) {
		/* the reason is kept by pointer: msg goes in the text */
		stray_error_at(err, STRAY_EIO, st->a.png, 0, "--png",
			       "cannot write");
		stray_error_text(err, msg);
		return STRAY_EIO;
	}
	return STRAY_OK;
}

/* The catalogue's stars through the --attitude camera (the head's +z the
 * boresight at the detector centre, an ideal lens). */
static int catalogue_stars(struct frames_job *st, double f0_e, size_t *n,
			   struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s->sensor;
	struct stray_cat_star *cat = malloc(FRAMES_MAX_STARS * sizeof(*cat));
	struct stray_camera cam;
	size_t n_cat;

	if (!cat)
		return stray_error_set(err, STRAY_ENOMEM, "frames", "out of memory");
	if (st->a.catalogue) {	/* the real sky (frames_sky.c) */
		free(cat);
		return frames_sky_stars(st->a.catalogue, sn, st->a.att,
					st->a.epoch, st->col0, st->row0,
					st->cols, st->rows, st->a.mag_max, f0_e,
					st->stars, FRAMES_MAX_STARS, n, err);
	}
	stray_q_dcm(st->a.att, cam.m_ih);
	cam.f_px = stray_sensor_focal_length_mm(sn) / (sn->pixel_pitch_um * 1e-3);
	cam.cx = 0.5 * sn->pixels_x - st->col0;
	cam.cy = 0.5 * sn->pixels_y - st->row0;
	stray_catalogue_cone(STRAY_CATALOGUE_SEED, cam.m_ih[2],
			     atan(0.5 * hypot(sn->pixels_x, sn->pixels_y) /
				  cam.f_px) * 180.0 / 3.14159265358979323846 + 0.5,
			     st->a.mag_max, cat, FRAMES_MAX_STARS, &n_cat);
	*n = stray_camera_stars(&cam, cat, n_cat, st->cols, st->rows, 8.0, f0_e,
				st->stars, FRAMES_MAX_STARS);
	free(cat);
	return STRAY_OK;
}

/* Render, detect and count every frame. */
static int run_frames(struct frames_job *st, struct stray_error *err)
{
	struct stray_frame_cfg c;
	struct stray_star_field f;
	double min_e = 0.0;	/* any true star, however faint, is not false */
	size_t n_stars, t, nt = (size_t)st->ev[0].tiles_x * st->ev[0].tiles_y;
	char msg[256];
	int i, d, rc;

	frame_cfg(st, &c);
	f.fov_deg2 = frames_fov_deg2(&st->s->sensor, st->cols, st->rows);
	f.mag_min = -1.5;
	f.mag_max = st->a.mag_max;
	/* eq. 2.2 and 2.12: F_0 t_exp A_cs, the e- of an m = 0 star */
	f.f0_e = st->s->flux.zero_mag * st->fm.m.t_exp_s * st->fm.m.a_cs_m2;
	if ((rc = open_store(st, err)) != STRAY_OK)
		return rc;
	if (st->a.has_att && (rc = catalogue_stars(st, f.f0_e, &n_stars, err)))
		return rc;
	if (st->a.truth && (rc = frames_sky_truth_write(st->a.truth, st->stars,
			n_stars, (int)st->a.frames, err)) != STRAY_OK)
		return rc;
	for (i = 0; i < (int)st->a.frames; i++) {
		uint64_t seed = stray_frame_seed((uint64_t)st->a.seed, (uint64_t)i);

		/* a library caller's Ctrl-C (tracer/cancel.h): a frame at most */
		if (tracer_cancelled())
			return stray_error_set(err, STRAY_EIO, "frames",
					       "interrupted");

		if (!st->a.has_att)	/* else the catalogue's, every frame */
			stray_star_field_draw(&f, st->cols, st->rows, seed,
					      st->stars, FRAMES_MAX_STARS, &n_stars);
		st->stars_sum += (double)n_stars;
		stray_frame_expect(&c, st->stars, n_stars, st->expect);
		stray_frame_sample(&c, st->expect, seed + 1, st->dn);
		if (st->a.on_frame && (rc = st->a.on_frame(st->a.on_frame_user,
				st->dn, st->cols, st->rows, (size_t)i,
				(size_t)st->a.frames, err)) != STRAY_OK)
			return rc;
		if (frames_detect(st->dn, st->cols, st->rows, &st->dc,
				  FRAMES_DET_THESIS | FRAMES_DET_THRESHOLD,
				  st->out, st->tiles, msg, sizeof(msg))) {
			stray_error_at(err, STRAY_EIO, NULL, 0, "opencv",
				       "star detection failed");
			stray_error_text(err, msg);
			return STRAY_EIO;
		}
		for (t = 0; t < nt; t++)
			st->ev[0].tile_sum[t] += st->tiles[t];
		for (d = 0; d < 2; d++) {
			/* The window sum places a star only to within its
			 * window (radius r); the threshold detector's
			 * centroids to a few px. */
			double match = d == 0 ? st->dc.window_radius_px : 4.0;
			size_t nf = frames_count_false(&st->out[d], st->stars,
				n_stars, min_e, match, st->ev[d].fx, st->ev[d].fy,
				&st->ev[d].n_f, st->ev[d].max_f);

			st->n_false[d] += (long)nf;
			st->n_false_sq[d] += (double)nf * (double)nf;
			st->n_found[d] += (long)(st->out[d].n - nf);
			st->ev[d].frames = i + 1;
		}
		{
			double match[2] = { FRAMES_REACH_PX, 4.0 };

			frames_lost_set_frame(&st->lost, st->tiles,
				st->ev[0].tiles_x, st->ev[0].tiles_y, 128,
				st->weight, st->cols, st->rows);
			frames_lost_add(&st->lost, st->out, match, st->stars,
					n_stars);
		}
		if (st->a.out_dir && i < (int)st->a.save &&
		    (rc = save_frame(st, i, n_stars, err)) != STRAY_OK)
			return rc;
		if (st->a.png && i == 0 && (rc = save_png(st, err)) != STRAY_OK)
			return rc;
	}
	return close_store(st, 1, err);
}

static void det_result(const struct frames_job *st, int d,
		       struct frames_det_result *r)
{
	double n = st->a.frames;

	r->name = d == 0 ? "thesis" : "threshold";
	r->measured = st->n_false[d] / n;
	/* Poisson, or the frames' own scatter when larger: false stars
	 * cluster where the background estimate errs (a map's structure,
	 * frames_mapterm.h), so counts are over-dispersed */
	r->sigma = sqrt((double)st->n_false[d]) / n;
	if (n > 1) {
		double var = (st->n_false_sq[d] - n * r->measured * r->measured) /
			     (n - 1);

		r->dispersion = r->measured > 0 ? var / r->measured : NAN;
		r->sigma = fmax(r->sigma, sqrt(fmax(var, 0.0) / n));
	} else {
		r->dispersion = NAN;
	}
	r->found = st->n_found[d] / n;
	r->extended = d == 0 ? st->rates.sliding : st->rates.clusters;
	r->extended_no_map_term = st->weight ? st->flat[d] : r->extended;
	if (!frames_saturation_verdict(st->clip_frac, r->verdict,
				       sizeof(r->verdict)))
		frames_diagnose(&st->fm, &st->ev[d], r->measured, r->extended,
				128, r->verdict, sizeof(r->verdict));
}

int frames_run(struct frames_job *job, const struct fdr_setup *s,
	       const struct frames_opts *o, struct stray_error *err)
{
	int rc;

	job->s = s;
	job->a = *o;
	rc = setup_frame(job, err);
	if (rc == STRAY_OK)
		rc = setup_map(job, err);
	if (rc == STRAY_OK)
		rc = setup_model(job, err);
	if (rc == STRAY_OK)
		rc = run_frames(job, err);
	if (rc == STRAY_OK) {
		det_result(job, 0, &job->res[0]);
		det_result(job, 1, &job->res[1]);
	}
	return rc;
}

void frames_job_free(struct frames_job *job)
{
	state_free(job);
}
