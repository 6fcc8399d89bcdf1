/*
 * cmd_reduce.c - `stray reduce`: a lab sweep folder (FITS frames and
 * manifest.csv, docs/formats.md) to the lens attenuation curve, its noise
 * floor and its ghosts (thesis §3.2, eq. 3.4-3.15, figs. 3.7-3.9).
 *
 * This file parses the options and prints; the reduction is one library
 * call, stray_reduce_sweep (libstray/reduce, stray/reduce_sweep.h), which
 * reads the folder through the sweep store (libstray/sweep).
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "cli_capture.h"
#include "commands.h"
#include "reduce_report.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "stray/reduce_sweep.h"

static const char usage[] =
	"usage: stray reduce SWEEP_DIR [SWEEP_DIR...] --out C.csv\n"
	"                    [--zemax F.DAT] [--json] [options]\n"
	"\n"
	"Several folders of one lens (the same window) are reduced together:\n"
	"each with its own darks, their visits on one time line (date_obs),\n"
	"one curve; one on-axis (0 deg) visit among them is enough.\n"
	"\n"
	"The lens attenuation curve from a lab sweep: darks per Bayer read\n"
	"channel, J = L_ful/(t1 nd1) - L_amb/(t2 nd2) (eq. 3.6), P(theta)\n"
	"(eq. 3.9), alpha = P/P(0) (eq. 3.12) with a standard error per point\n"
	"and the noise floor (eq. 3.15); hot, dead and saturated pixels kept\n"
	"out; source drift from on-axis revisits; ghosts tracked over angle.\n"
	"\n"
	"  --out C.csv          attenuation curve (theta_deg,alpha,sigma,\n"
	"                       noise_floor) (required)\n"
	"  --zemax F.DAT        the curve as an OpticStudio TABLE coating\n"
	"  --coating-name N     its name (default LENS_ATTEN)\n"
	"  --wave-um W          its wavelength in micrometres (default 0.55)\n"
	"  --channels MAP       read channel per (row%2)*4+col%4, 8 digits\n"
	"                       (default 01234567)\n"
	"  --row-filter         3-pixel row-neighbour mean (thesis §3.2)\n"
	"  --hot-sigma S        hot/dead pixel threshold, robust sigmas (6)\n"
	"  --ghost-window N     ghost background window, columns (41)\n"
	"  --ghost-z Z          ghost peak significance (6)\n"
	"  --no-verify          skip the manifest's SHA-256 check\n"
	"  --plot-dir DIR       alpha.png, profiles.png, ghosts.png, j.png\n"
	"  --image-angle DEG    angle of the J image and map (default 0)\n"
	"  --map M.csv          J at --image-angle as a region map for\n"
	"                       `stray fdr --map` (fraction,rel_alpha)\n"
	"  --map-regions N      regions of that map (default 16, max 64)\n"
	"  --json               machine-readable output (ghosts, curve, pixels)\n";

struct reduce_args {
	char *const *dirs;	/* the sweep folders, n_dirs of them */
	int n_dirs;
	const char *dir, *out, *zemax, *coating, *plot_dir, *map;
	double wave_um;
	size_t map_regions;
};

static int parse_size(const char *opt, const char *text, size_t *out)
{
	double v;
	int rc = cli_parse_double("reduce", opt, text, &v);

	if (rc != CLI_OK)
		return rc;
	if (!(v >= 1 && v <= 100001 && v == floor(v)))
		return cli_usage_error("reduce", "option '--%s': '%s' must be a"
				       " whole number >= 1", opt, text);
	*out = (size_t)v;
	return CLI_OK;
}

static int take_option(int opt, struct reduce_args *a,
		       struct stray_reduce_sweep_opts *o)
{
	struct stray_error err;

	stray_error_clear(&err);
	switch (opt) {
	case 'o': a->out = optarg; return CLI_OK;
	case 'z': a->zemax = optarg; return CLI_OK;
	case 'n': a->coating = optarg; return CLI_OK;
	case 'P': a->plot_dir = optarg; return CLI_OK;
	case 'm': a->map = optarg; return CLI_OK;
	case 'R': return parse_size("map-regions", optarg, &a->map_regions);
	case 'w': return cli_parse_double("reduce", "wave-um", optarg,
					  &a->wave_um);
	case 'r': o->response.row_filter = 1; return CLI_OK;
	case 'V': o->verify_sha256 = 0; return CLI_OK;
	case 's': return cli_parse_double("reduce", "hot-sigma", optarg,
					  &o->hot_sigma);
	case 'Z': return cli_parse_double("reduce", "ghost-z", optarg,
					  &o->ghost.min_z);
	case 'W': return parse_size("ghost-window", optarg, &o->ghost.window);
	case 'i':
		o->keep_image = 1;
		return cli_parse_double("reduce", "image-angle", optarg,
					&o->image_theta_deg);
	case 'c':
		if (stray_bayer_parse(optarg, &o->map, &err) != STRAY_OK)
			return cli_usage_error("reduce",
					       "option '--channels': '%s':"
					       " %s", optarg, err.reason);
		return CLI_OK;
	}
	return CLI_USAGE;
}

static int parse_args(int argc, char **argv, struct reduce_args *a,
		      struct stray_reduce_sweep_opts *o)
{
	static const struct option opts[] = {
		{ "out", required_argument, NULL, 'o' },
		{ "zemax", required_argument, NULL, 'z' },
		{ "coating-name", required_argument, NULL, 'n' },
		{ "wave-um", required_argument, NULL, 'w' },
		{ "channels", required_argument, NULL, 'c' },
		{ "row-filter", no_argument, NULL, 'r' },
		{ "hot-sigma", required_argument, NULL, 's' },
		{ "ghost-window", required_argument, NULL, 'W' },
		{ "ghost-z", required_argument, NULL, 'Z' },
		{ "no-verify", no_argument, NULL, 'V' },
		{ "plot-dir", required_argument, NULL, 'P' },
		{ "image-angle", required_argument, NULL, 'i' },
		{ "map", required_argument, NULL, 'm' },
		{ "map-regions", required_argument, NULL, 'R' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc;

	while ((rc = cli_next_option("reduce", argc, argv, opts, usage,
				     &opt)) == CLI_OK && opt != -1)
		if ((rc = take_option(opt, a, o)) != CLI_OK)
			return rc;
	if (rc != CLI_OK)
		return rc;
	if (optind >= argc)
		return cli_usage_error("reduce", "SWEEP_DIR is required");
	a->dir = argv[optind];
	a->dirs = argv + optind;
	a->n_dirs = argc - optind;
	if (!a->out)
		return cli_usage_error("reduce", "--out is required");
	if (!(o->hot_sigma > 0.0) || !(o->ghost.min_z > 0.0) ||
	    !(a->wave_um > 0.0))
		return cli_usage_error("reduce", "--hot-sigma, --ghost-z and"
				       " --wave-um must be > 0");
	if (o->ghost.window < 9)
		return cli_usage_error("reduce", "option '--ghost-window': must"
				       " be at least 9 columns");
	if (!(o->ghost.window % 2))
		o->ghost.window++;	/* the window has a centre column */
	return CLI_OK;
}

/* The curve CSV (docs/formats.md) with noise_floor and provenance. */
static int save_curve(const struct reduce_args *a,
		      const struct stray_reduce_sweep_result *r, struct stray_error *err)
{
	struct stray_curve c;
	double *nf = calloc(r->n_points ? r->n_points : 1, sizeof(double));
	char text[128];
	size_t i;
	int rc;

	memset(&c, 0, sizeof(c));
	if (!nf)
		return stray_error_set(err, STRAY_ENOMEM, "curve", "no memory");
	rc = stray_curve_alloc(&c, r->n_points, 1, err);
	for (i = 0; rc == STRAY_OK && i < r->n_points; i++) {
		c.theta_deg[i] = r->points[i].theta_deg;
		c.alpha[i] = r->points[i].alpha;
		c.sigma[i] = r->points[i].sigma;
		nf[i] = r->points[i].noise_floor;
	}
	snprintf(text, sizeof(text), "%zu frames, %zu hot, %zu dead pixels,"
		 " drift %+.3g%% (%.1f sigma)", r->n_frames, r->mask.n_hot,
		 r->mask.n_dead, 100.0 * r->drift.rel_change, r->drift.z);
	if (rc == STRAY_OK)
		rc = stray_curve_add_column(&c, "noise_floor", nf, err);
	if (rc == STRAY_OK)
		rc = stray_curve_add_meta(&c, "kind", "lens", err);
	if (rc == STRAY_OK)
		rc = stray_curve_add_meta(&c, "source", a->dir, err);
	if (rc == STRAY_OK)
		rc = stray_curve_add_meta(&c, "reduction", text, err);
	if (rc == STRAY_OK)	/* a library call's curve (cli_capture.h) */
		rc = cli_capture_curve(&c, err);
	if (rc == STRAY_OK)
		rc = stray_curve_save(a->out, &c, err);
	stray_curve_free(&c);
	free(nf);
	return rc;
}

static int write_outputs(const struct reduce_args *a,
			 const struct stray_reduce_sweep_result *r, struct stray_error *err)
{
	int rc = save_curve(a, r, err);

	if (rc == STRAY_OK && a->zemax)
		rc = reduce_write_zemax(a->zemax, a->coating, a->wave_um, r,
					err);
	if (rc == STRAY_OK && a->plot_dir)
		rc = reduce_plots(a->plot_dir, r, err);
	if (rc == STRAY_OK && a->map)
		rc = reduce_write_map(a->map, (unsigned)a->map_regions, r, err);
	return rc;
}

int cmd_reduce(int argc, char **argv)
{
	struct reduce_args a = { NULL, 0, NULL, NULL, NULL, "LENS_ATTEN", NULL,
				 NULL, 0.55, 16 };
	struct stray_reduce_sweep_opts o;
	struct stray_reduce_sweep_result r;
	struct stray_error err;
	int rc, i;

	stray_reduce_sweep_opts_default(&o);
	rc = parse_args(argc, argv, &a, &o);
	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	if ((a.plot_dir || a.map) && !o.keep_image)
		o.keep_image = 1;	/* J at 0 deg unless told otherwise */
	stray_error_clear(&err);
	for (i = 0; i < a.n_dirs; i++) {
		struct stat st;

		if (stat(a.dirs[i], &st) == 0 && !S_ISDIR(st.st_mode)) {
			stray_error_at(&err, STRAY_EINVAL, a.dirs[i], 0,
				"SWEEP", "is a file, not a sweep folder (a "
				"folder with manifest.csv)");
			return cli_fail("reduce", &err);
		}
		reduce_warn_partial(a.dirs[i]);
	}
	stray_file_defer();	/* every output renamed at the end, or none */
	rc = a.n_dirs == 1 ? stray_reduce_sweep(a.dir, &o, &r, &err)
			   : stray_reduce_sweeps((const char *const *)a.dirs,
						 (size_t)a.n_dirs, &o, &r,
						 &err);
	if (rc == STRAY_OK)
		rc = write_outputs(&a, &r, &err);
	if (stray_file_finish(rc == STRAY_OK, &err) != STRAY_OK &&
	    rc == STRAY_OK)
		rc = STRAY_EIO;
	if (rc != STRAY_OK) {
		stray_reduce_sweep_result_free(&r);
		return cli_fail("reduce", &err);
	}
	if (cli.json)
		rc = cli_json_emit(reduce_json(&r, a.out));
	else
		reduce_print(stdout, &r, a.out);
	stray_reduce_sweep_result_free(&r);
	return rc;
}
