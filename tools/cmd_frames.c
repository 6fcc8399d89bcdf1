/*
 * cmd_frames.c - `stray frames`: detector frames rendered for a source at
 * theta (eq. 2.3 with k_px, stars by eq. 2.2 and 2.12, camera noise), run
 * through two star detectors, false stars counted and set against the
 * FDR model (eq. 2.18) and its extension (stray/fdr_field.h); issue 13
 * items 3-5.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "fdr_setup.h"
#include "focal_map_io.h"
#include "frames_io.h"
#include "frames_lost.h"
#include "frames_mapterm.h"
#include "frames_plot.h"
#include "frames_run.h"
#include "frames_sat.h"
#include "image_cv.h"
#include "stray/aem.h"
#include "stray/catalogue.h"
#include "frames_sky.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/sensor_geom.h"
#include "stray/sweep_store.h"

static const char usage[] =
	"usage: stray frames (--curve C.csv --theta DEG | --alpha A) [--frames N]\n"
	"                    [--window PX] [--seed K] [--detector thesis|threshold]\n"
	"                    [--normalisation thesis|consistent] [--map M.fits]\n"
	"                    [--out-dir D] [--save N] [--json] [options]\n"
	"\n"
	"Render detector frames for the Sun at theta off boresight, detect stars\n"
	"and count the false ones against the FDR model (thesis eq. 2.18) and its\n"
	"extension to the real detectors.  Stars are a synthetic field (no\n"
	"catalogue is installed): all-sky average counts, magnitudes up to 10.\n"
	"\n"
	"  --curve C.csv       system attenuation curve; alpha = curve(theta)\n"
	"  --theta DEG         source angle off boresight (0..180)\n"
	"  --alpha A           the attenuation itself, instead of a curve\n"
	"  --frames N          frames to render (1)\n"
	"  --window PX         a PX x PX window at the detector centre (full frame)\n"
	"  --seed K            random seed (1): the same seed, the same frames\n"
	"  --detector D        thesis (window sum vs I_sdt, default) or threshold\n"
	"                      (k sigma above a local background, >= 5 px); both\n"
	"                      run, D picks the top-level keys\n"
	NORMALISATION_USAGE
	"  --map M.fits        focal-plane stray-light map (stray trace --focal-map):\n"
	"                      its shape spreads the stray light, alpha sets the level\n"
	"  --out-dir D         the first --save (3) frames as a sweep folder\n"
	"                      (manifest.csv + FITS); D must not exist or be empty\n"
	"  --mag-max M         faintest star rendered (10)\n"
	"  --catalogue CAT     with --attitude: the stars of a real catalogue\n"
	"                      (hip2.dat, hip_main.dat, BSC5, CSV) at --epoch\n"
	"                      (Julian year, 2000), colours through the QE\n"
	"  --truth-stars T.csv with --attitude: every star rendered (frame,\n"
	"                      x_px, y_px, v_mag, electrons)\n"
	"  --attitude Q        q_c,e1,e2,e3: the head's attitude (CCSDS 504.0 q_ib,\n"
	"                      boresight +z): stars from the synthetic catalogue\n"
	"                      (stray/catalogue.h) at their sky places, the same in\n"
	"                      every frame, instead of a random field\n"
	"  --png F.png         the first frame in false colour (log scale)\n"
	"  --plot-validation V.csv --plot F.png\n"
	"                      only draw measured vs predicted false stars from the\n"
	"                      table scripts/validate-frames.sh writes\n"
	"  --json              machine-readable output\n"
	SENSOR_USAGE;

struct frames_args {
	const char *curve, *map, *out_dir, *png, *plot_csv, *plot;
	double theta_deg, alpha, frames, window, seed, save, mag_max;
	int has_theta, has_alpha, detector;
	double att[4];		/* --attitude q_ib; has_att = 0: random field */
	int has_att;
	const char *catalogue, *truth;	/* --catalogue, --truth-stars */
	double epoch;		/* --epoch, Julian year */
};

/* Solid angle of the rendered frame, through the ideal lens the focal
 * maps use (stray_sensor_pixel_deg). */
static double frames_fov_deg2(const struct stray_sensor *s, int cols,
			      int rows)
{
	double px_deg = stray_sensor_pixel_deg(s);

	return cols * px_deg * rows * px_deg;
}

static int parse_choice(const char *opt, const char *v, const char *a,
			const char *b, int *out)
{
	if (strcmp(v, a) && strcmp(v, b))
		return cli_usage_error("frames", "option '--%s': '%s' is not %s or %s",
				       opt, v, a, b);
	*out = strcmp(v, a) == 0;
	return CLI_OK;
}

/* --attitude q_c,e1,e2,e3 (normalised here). */
static int parse_attitude(const char *v, struct frames_args *a)
{
	double n;
	char tail;

	if (sscanf(v, "%lf,%lf,%lf,%lf%c", &a->att[0], &a->att[1], &a->att[2],
		   &a->att[3], &tail) != 4)
		return cli_usage_error("frames", "option '--attitude': '%s' is not q_c,e1,e2,e3", v);
	n = sqrt(a->att[0] * a->att[0] + a->att[1] * a->att[1] +
		 a->att[2] * a->att[2] + a->att[3] * a->att[3]);
	if (!(n > 1e-9) || !isfinite(n))
		return cli_usage_error("frames", "option '--attitude': '%s' is not a rotation", v);
	a->att[0] /= n;
	a->att[1] /= n;
	a->att[2] /= n;
	a->att[3] /= n;
	a->has_att = 1;
	return CLI_OK;
}

static int parse_opt(struct fdr_setup *s, struct frames_args *a, int opt)
{
	switch (opt) {
	case 'c': a->curve = optarg; return CLI_OK;
	case 'm': a->map = optarg; return CLI_OK;
	case 'o': a->out_dir = optarg; return CLI_OK;
	case 'P': a->png = optarg; return CLI_OK;
	case 'V': a->plot_csv = optarg; return CLI_OK;
	case 'p': a->plot = optarg; return CLI_OK;
	case 't': a->has_theta = 1;
		return cli_parse_double("frames", "theta", optarg, &a->theta_deg);
	case 'a': a->has_alpha = 1;
		return cli_parse_double("frames", "alpha", optarg, &a->alpha);
	case 'n': return cli_parse_count("frames", "frames", optarg, 1, 1e6,
					 &a->frames);
	case 'w': return cli_parse_count("frames", "window", optarg, 32, 4096,
					 &a->window);
	case 'k': return cli_parse_count("frames", "seed", optarg, 0, 4e9,
					 &a->seed);
	case 'v': return cli_parse_count("frames", "save", optarg, 0, 1000,
					 &a->save);
	case 'g': return cli_parse_double("frames", "mag-max", optarg,
					  &a->mag_max);
	case 'd': return parse_choice("detector", optarg, "thesis", "threshold",
				      &a->detector);
	case 'q': return parse_attitude(optarg, a);
	case 'C': a->catalogue = optarg; return CLI_OK;
	case 'T': a->truth = optarg; return CLI_OK;
	case 'E': return cli_parse_double("frames", "epoch", optarg, &a->epoch);
	default: {
		int rc = fdr_setup_option(s, "frames", opt, optarg);
		return rc == 1 ? CLI_OK : rc ? rc : CLI_USAGE;
	}
	}
}

static int check_args(const struct frames_args *a)
{
	if (a->plot_csv || a->plot)
		return a->plot_csv && a->plot ? CLI_OK : cli_usage_error("frames",
			"--plot-validation and --plot go together");
	if (a->has_alpha == (a->curve != NULL))
		return cli_usage_error("frames", "give --curve with --theta, or --alpha");
	if ((a->catalogue || a->truth) && !a->has_att)
		return cli_usage_error("frames", "--catalogue and --truth-stars need --attitude");
	if (!(a->epoch > 1000.0 && a->epoch < 3000.0))
		return cli_usage_error("frames", "option '--epoch': %g is not a Julian year in 1000..3000",
				       a->epoch);
	if (a->curve && !a->has_theta)
		return cli_usage_error("frames", "--curve needs --theta");
	if (a->has_theta && !(a->theta_deg >= 0.0 && a->theta_deg <= 180.0))
		return cli_usage_error("frames", "option '--theta': %g is outside 0..180 deg",
				       a->theta_deg);
	if (a->has_alpha && !(a->alpha >= 0.0))
		return cli_usage_error("frames", "option '--alpha': %g must be >= 0",
				       a->alpha);
	if (!(a->mag_max > -2.0 && a->mag_max <= 14.0))
		return cli_usage_error("frames", "option '--mag-max': %g is outside -2..14",
				       a->mag_max);
	return CLI_OK;
}

static int parse_args(int argc, char **argv, struct fdr_setup *s,
		      struct frames_args *a)
{
	static const struct option opts[] = {
		SENSOR_LONG_OPTIONS,
		{ "curve", required_argument, NULL, 'c' },
		{ "theta", required_argument, NULL, 't' },
		{ "alpha", required_argument, NULL, 'a' },
		{ "frames", required_argument, NULL, 'n' },
		{ "window", required_argument, NULL, 'w' },
		{ "seed", required_argument, NULL, 'k' },
		{ "save", required_argument, NULL, 'v' },
		{ "mag-max", required_argument, NULL, 'g' },
		{ "attitude", required_argument, NULL, 'q' },
		{ "catalogue", required_argument, NULL, 'C' },
		{ "truth-stars", required_argument, NULL, 'T' },
		{ "epoch", required_argument, NULL, 'E' },
		{ "detector", required_argument, NULL, 'd' },
		NORMALISATION_LONG_OPTION,
		{ "map", required_argument, NULL, 'm' },
		{ "out-dir", required_argument, NULL, 'o' },
		{ "png", required_argument, NULL, 'P' },
		{ "plot-validation", required_argument, NULL, 'V' },
		{ "plot", required_argument, NULL, 'p' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc;

	while ((rc = cli_next_option("frames", argc, argv, opts, usage,
				     &opt)) == CLI_OK && opt != -1)
		if ((rc = parse_opt(s, a, opt)) != CLI_OK)
			return rc;
	if (rc == CLI_OK)
		rc = cli_no_operands("frames", argc, argv);
	return rc == CLI_OK ? check_args(a) : rc;
}

#define MAX_DET 200000
#define MAX_STARS 200000
#define MAX_FALSE_POS 200000

struct frames_state {
	struct fdr_setup s;
	struct frames_args a;
	int cols, rows, col0, row0;
	double k_px, alpha, wmean, stars_sum;
	double clip_frac;		/* pixels whose background clips */
	double resid_rel;		/* the map's background-error term */
	double flat[2];			/* extended rates without it */
	float *weight, *expect, *tiles;
	uint16_t *dn;
	struct stray_star *stars;
	struct frames_detection *det;
	struct frames_detect_out out[2];
	struct frames_detect_cfg dc;
	struct frames_model fm;
	struct frames_rates rates;
	struct frames_alpha_req req;
	struct stray_region_map map;
	struct frames_evidence ev[2];
	struct frames_lost lost;	/* stars found per magnitude (issue 28) */
	long n_false[2], n_found[2];
	double n_false_sq[2];		/* sum of per-frame counts squared */
	uint16_t *det_rows;		/* detector row of each frame row */
	struct stray_dir_out dir;	/* --out-dir, filled as a temporary */
	struct stray_sweep_manifest mf;
	int dir_open, store_open;
};

static int close_store(struct frames_state *st, int ok,
		       struct stray_error *err);

static void state_free(struct frames_state *st)
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
static int setup_frame(struct frames_state *st, struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s.sensor;
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
	st->k_px = fdr_setup_k_px(&st->s);
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
	st->stars = malloc(MAX_STARS * sizeof(*st->stars));
	st->det = malloc(2 * MAX_DET * sizeof(*st->det));
	st->tiles = malloc((size_t)tx * ty * sizeof(float));
	st->ev[0].tile_sum = calloc((size_t)tx * ty, sizeof(double));
	for (i = 0; i < 2; i++) {
		st->ev[i].tiles_x = tx;
		st->ev[i].tiles_y = ty;
		st->ev[i].max_f = MAX_FALSE_POS;
		st->ev[i].fx = malloc(MAX_FALSE_POS * sizeof(float));
		st->ev[i].fy = malloc(MAX_FALSE_POS * sizeof(float));
		st->out[i].det = st->det + i * MAX_DET;
		st->out[i].max = MAX_DET;
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
static int setup_map(struct frames_state *st, struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s.sensor;
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

static int setup_model(struct frames_state *st, struct stray_error *err)
{
	int rc = frames_model_init(&st->fm, &st->s.sensor, st->s.flux.sun,
				   st->s.flux.drs, st->k_px,
				   st->alpha * st->wmean, st->cols, st->rows,
				   st->a.map ? &st->map : NULL, err);

	if (rc == STRAY_OK)
		rc = frames_model_rates(&st->fm, &st->rates, err);
	if (rc == STRAY_OK)
		rc = frames_alpha_required(&st->fm, &st->s.sensor, st->k_px,
					   st->s.rate, &st->req, err);
	frames_detect_cfg_init(&st->dc, &st->fm, &st->s.sensor);
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

static void frame_cfg(const struct frames_state *st, struct stray_frame_cfg *c)
{
	const struct stray_sensor *sn = &st->s.sensor;

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
static int open_store(struct frames_state *st, struct stray_error *err)
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
static int close_store(struct frames_state *st, int ok,
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
static int save_frame(struct frames_state *st, int i, size_t n_stars,
		      struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s.sensor;
	struct stray_sweep_key k[] = {
		{ "ALPHA", STRAY_SWEEP_KEY_DOUBLE, st->alpha, 0, NULL,
		  "system attenuation" },
		{ "KPX", STRAY_SWEEP_KEY_DOUBLE, st->k_px, 0, NULL,
		  "k_px = A_cs/(n_px A_px)" },
		{ "NORM", STRAY_SWEEP_KEY_STRING, 0.0, 0,
		  stray_normalisation_name(st->s.normalisation),
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
static int save_png(struct frames_state *st, struct stray_error *err)
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
static int catalogue_stars(struct frames_state *st, double f0_e, size_t *n,
			   struct stray_error *err)
{
	const struct stray_sensor *sn = &st->s.sensor;
	struct stray_cat_star *cat = malloc(MAX_STARS * sizeof(*cat));
	struct stray_camera cam;
	size_t n_cat;

	if (!cat)
		return stray_error_set(err, STRAY_ENOMEM, "frames", "out of memory");
	if (st->a.catalogue) {	/* the real sky (frames_sky.c) */
		free(cat);
		return frames_sky_stars(st->a.catalogue, sn, st->a.att,
					st->a.epoch, st->col0, st->row0,
					st->cols, st->rows, st->a.mag_max, f0_e,
					st->stars, MAX_STARS, n, err);
	}
	stray_q_dcm(st->a.att, cam.m_ih);
	cam.f_px = stray_sensor_focal_length_mm(sn) / (sn->pixel_pitch_um * 1e-3);
	cam.cx = 0.5 * sn->pixels_x - st->col0;
	cam.cy = 0.5 * sn->pixels_y - st->row0;
	stray_catalogue_cone(STRAY_CATALOGUE_SEED, cam.m_ih[2],
			     atan(0.5 * hypot(sn->pixels_x, sn->pixels_y) /
				  cam.f_px) * 180.0 / 3.14159265358979323846 + 0.5,
			     st->a.mag_max, cat, MAX_STARS, &n_cat);
	*n = stray_camera_stars(&cam, cat, n_cat, st->cols, st->rows, 8.0, f0_e,
				st->stars, MAX_STARS);
	free(cat);
	return STRAY_OK;
}

/* Render, detect and count every frame. */
static int run_frames(struct frames_state *st, struct stray_error *err)
{
	struct stray_frame_cfg c;
	struct stray_star_field f;
	double min_e = 0.0;	/* any true star, however faint, is not false */
	size_t n_stars, t, nt = (size_t)st->ev[0].tiles_x * st->ev[0].tiles_y;
	char msg[256];
	int i, d, rc;

	frame_cfg(st, &c);
	f.fov_deg2 = frames_fov_deg2(&st->s.sensor, st->cols, st->rows);
	f.mag_min = -1.5;
	f.mag_max = st->a.mag_max;
	/* eq. 2.2 and 2.12: F_0 t_exp A_cs, the e- of an m = 0 star */
	f.f0_e = st->s.flux.zero_mag * st->fm.m.t_exp_s * st->fm.m.a_cs_m2;
	if ((rc = open_store(st, err)) != STRAY_OK)
		return rc;
	if (st->a.has_att && (rc = catalogue_stars(st, f.f0_e, &n_stars, err)))
		return rc;
	if (st->a.truth && (rc = frames_sky_truth_write(st->a.truth, st->stars,
			n_stars, (int)st->a.frames, err)) != STRAY_OK)
		return rc;
	for (i = 0; i < (int)st->a.frames; i++) {
		uint64_t seed = stray_frame_seed((uint64_t)st->a.seed, (uint64_t)i);

		if (!st->a.has_att)	/* else the catalogue's, every frame */
			stray_star_field_draw(&f, st->cols, st->rows, seed,
					      st->stars, MAX_STARS, &n_stars);
		st->stars_sum += (double)n_stars;
		stray_frame_expect(&c, st->stars, n_stars, st->expect);
		stray_frame_sample(&c, st->expect, seed + 1, st->dn);
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

struct det_result {
	const char *name;
	double measured, sigma, extended, found;
	double dispersion;		/* frame-to-frame variance / mean */
	char verdict[512];
};

static void det_result(const struct frames_state *st, int d,
		       struct det_result *r)
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
	if (!frames_saturation_verdict(st->clip_frac, r->verdict,
				       sizeof(r->verdict)))
		frames_diagnose(&st->fm, &st->ev[d], r->measured, r->extended,
				128, r->verdict, sizeof(r->verdict));
}

static double ratio(double model, double measured)
{
	return measured > 0.0 ? model / measured : NAN;
}

static void add_det(cJSON *o, const struct frames_state *st,
		    const struct det_result *r)
{
	cJSON_AddStringToObject(o, "detector", r->name);
	cJSON_AddItemToObject(o, "false_stars_per_image", cli_json_number(r->measured));
	cJSON_AddItemToObject(o, "false_stars_sigma", cli_json_number(r->sigma));
	cJSON_AddItemToObject(o, "false_stars_dispersion", cli_json_number(r->dispersion));
	cJSON_AddItemToObject(o, "model_fdr", cli_json_number(st->rates.model));
	cJSON_AddItemToObject(o, "model_fdr_thesis", cli_json_number(st->rates.thesis));
	cJSON_AddItemToObject(o, "model_fdr_extended", cli_json_number(r->extended));
	cJSON_AddItemToObject(o, "model_fdr_extended_no_map_term", cli_json_number(
		st->weight ? st->flat[strcmp(r->name, "thesis") ? 1 : 0] :
			     r->extended));
	cJSON_AddItemToObject(o, "ratio_before", cli_json_number(ratio(st->rates.model, r->measured)));
	cJSON_AddItemToObject(o, "ratio_after", cli_json_number(ratio(r->extended, r->measured)));
	cJSON_AddItemToObject(o, "stars_found_per_image", cli_json_number(r->found));
	cJSON_AddStringToObject(o, "verdict", r->verdict);
}

static int print_json(const struct frames_state *st,
		      const struct det_result r[2])
{
	cJSON *o = cJSON_CreateObject(), *ds = cJSON_CreateObject(), *s;
	int top = st->a.detector ? 0 : 1, d;

	cJSON_AddStringToObject(o, "sensor", st->s.sensor.name);
	cJSON_AddItemToObject(o, "theta_deg", cli_json_number(st->a.has_theta ? st->a.theta_deg : NAN));
	cJSON_AddItemToObject(o, "alpha", cli_json_number(st->alpha));
	cJSON_AddItemToObject(o, "frames", cli_json_number(st->a.frames));
	cJSON_AddItemToObject(o, "cols", cli_json_number(st->cols));
	cJSON_AddItemToObject(o, "rows", cli_json_number(st->rows));
	fdr_setup_json(&st->s, o);
	cJSON_AddStringToObject(o, "stray_light", st->a.map ? st->a.map : "uniform");
	cJSON_AddItemToObject(o, "stray_e_per_px", cli_json_number(st->fm.stray_e));
	cJSON_AddItemToObject(o, "clipped_fraction", cli_json_number(st->clip_frac));
	cJSON_AddItemToObject(o, "bg_resid_rel", cli_json_number(st->resid_rel));
	cJSON_AddItemToObject(o, "threshold_e", cli_json_number(st->fm.i_sdt_e));
	cJSON_AddItemToObject(o, "pixel_threshold_e", cli_json_number(st->fm.pixel_threshold_e));
	cJSON_AddItemToObject(o, "window_px", cli_json_number(st->fm.win.n_px));
	s = cJSON_AddObjectToObject(o, "alpha_required");
	cJSON_AddItemToObject(s, "rate", cli_json_number(st->s.rate));
	cJSON_AddItemToObject(s, "thesis_k1", cli_json_number(st->req.thesis_k1));
	cJSON_AddItemToObject(s, "model", cli_json_number(st->req.model));
	cJSON_AddItemToObject(s, "extended", cli_json_number(st->req.extended));
	s = cJSON_AddObjectToObject(o, "stars");
	cJSON_AddStringToObject(s, "source", st->a.catalogue ?
		"real catalogue (--catalogue) through --attitude" : st->a.has_att ?
		"synthetic catalogue (stray/catalogue.h) through --attitude" :
		"synthetic: all-sky average counts (no catalogue installed)");
	cJSON_AddItemToObject(s, "per_image", cli_json_number(st->stars_sum / st->a.frames));
	cJSON_AddItemToObject(s, "mag_max", cli_json_number(st->a.mag_max));
	add_det(o, st, &r[top]);
	for (d = 0; d < 2; d++)
		add_det(cJSON_AddObjectToObject(ds, r[d].name), st, &r[d]);
	cJSON_AddItemToObject(o, "detectors", ds);
	frames_lost_json(&st->lost, o);
	return cli_json_emit(o);
}

static void print_text(const struct frames_state *st,
		       const struct det_result r[2])
{
	int d;

	printf("Rendered frames (issue 13) for %s: %d x %d px, %g frames, alpha %.4g\n",
	       st->s.sensor.name, st->cols, st->rows, st->a.frames, st->alpha);
	printf("  normalisation %s, k_px %.3f: %.1f stray e-/px (eq. 2.3), %s\n",
	       stray_normalisation_name(st->s.normalisation), st->k_px,
	       st->fm.stray_e, st->a.map ? st->a.map : "uniform");
	printf("  stars: %s, %.0f per frame to m = %g\n",
	       st->a.catalogue ? "real catalogue through --attitude" :
	       st->a.has_att ? "synthetic catalogue through --attitude"
			     : "synthetic field (no catalogue)",
	       st->stars_sum / st->a.frames, st->a.mag_max);
	printf("  I_sdt %.1f e- (eq. 2.16), pixel threshold %.1f e-\n",
	       st->fm.i_sdt_e, st->fm.pixel_threshold_e);
	printf("  alpha for %g false stars per full image: %.3g (thesis, k_px = 1), %.3g (eq. 2.18 here), %.3g (extended)\n",
	       st->s.rate, st->req.thesis_k1, st->req.model, st->req.extended);
	for (d = 0; d < 2; d++)
		printf("  %-9s false stars %.4g +- %.2g per frame; model %.4g (thesis noise %.4g), extended %.4g\n"
		       "            %s\n", r[d].name, r[d].measured, r[d].sigma,
		       st->rates.model, st->rates.thesis, r[d].extended,
		       r[d].verdict);
	frames_lost_print(&st->lost);
}

int cmd_frames(int argc, char **argv)
{
	struct frames_state *st = calloc(1, sizeof(*st));
	struct det_result r[2];
	struct stray_error err;
	int rc;

	if (!st)
		return CLI_FAIL;
	fdr_setup_init(&st->s);
	stray_error_clear(&err);
	st->a.frames = 1;
	st->a.seed = 1;
	st->a.save = 3;
	st->a.mag_max = 10.0;
	st->a.epoch = 2000.0;
	st->a.detector = 1;
	rc = parse_args(argc, argv, &st->s, &st->a);
	if (rc == CLI_OK && st->a.plot_csv) {
		if (frames_plot_validation(st->a.plot_csv, st->a.plot, &err))
			rc = cli_fail("frames", &err);
	} else if (rc == CLI_OK) {
		if (fdr_setup_load(&st->s, &err) || setup_frame(st, &err) ||
		    setup_map(st, &err) || setup_model(st, &err) ||
		    run_frames(st, &err)) {
			rc = cli_fail("frames", &err);
		} else {
			det_result(st, 0, &r[0]);
			det_result(st, 1, &r[1]);
			if (cli.json)
				rc = print_json(st, r);
			else
				print_text(st, r);
		}
	}
	state_free(st);
	free(st);
	return rc < 0 ? CLI_OK : rc;
}
