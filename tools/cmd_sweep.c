/*
 * cmd_sweep.c - `stray sweep`: a grid of baffle designs, each traced
 * (by the caller's runner: threads, or MPI ranks under stray-mpi) and
 * judged by its Sun exclusion angle (thesis §5.1: the angle past which alpha
 * stays below the alpha_required of the FDR model, eq. 3.x via
 * stray_fdr_alpha_required) and alpha at chosen angles.  Resumable:
 * each finished design's curve is written atomically to the state
 * folder, and a design whose curve is there with the same run key is
 * read back instead of traced.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "design_sweep.h"
#include "fdr_options.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "trace_run.h"
#include "tracer/angles.h"
#include "tracer/runner.h"
#include "tracer/scene_load.h"

static const char usage[] =
	"usage: stray sweep --scene SCENE --grid key=v1,v2,... [--grid ...]\n"
	"                   --state DIR [--out T.csv] [--plot F.png] [--json]\n"
	"                   [--angles LIST] [--alpha-at LIST] [--rays N]\n"
	"                   [--seed K] [--threads T] [--batches B] [--lens L]\n"
	"                   [--set key=value]... [sensor options]\n"
	"       stray sweep import --log LOG.csv --out DIR FILE_OR_DIR...\n"
	"                   (frames of other software into a lab sweep folder:\n"
	"                   stray sweep import --help, docs/sweep-import.md)\n"
	"\n"
	"Traces every design of the grid (the Cartesian product of the --grid\n"
	"axes over 'stray trace --set' parameters) and tables its Sun\n"
	"exclusion angle and alpha at --alpha-at.  Each finished design's\n"
	"curve is kept in --state DIR (design_NNNN.csv); run again and the\n"
	"designs already there (same scene, rays, seed, angles) are skipped.\n"
	"\n"
	"  --grid key=v1,...   one axis (up to 8 axes, 32 values each)\n"
	"  --state DIR         folder of per-design curves (created)\n"
	"  --out T.csv         the table as CSV\n"
	"  --plot F.png        exclusion angle per design, with interval\n"
	"  --angles LIST       as 'stray trace' (default 0:30:5,30:90:1)\n"
	"  --alpha-at LIST     angles to report alpha at (default 20,30,40)\n"
	"  --rays N, --seed K, --threads T, --batches B, --lens L.csv,\n"
	"  --set key=value     as 'stray trace' (rays default 300000)\n"
	SENSOR_USAGE NORMALISATION_USAGE DETECTOR_USAGE;

/* The command line: the sweep (tracer/design_sweep.h) and its outputs. */
struct sweep_args {
	struct design_sweep job;
	const char *out, *plot;
};

static const struct option sweep_opts[] = {
	{ "scene", required_argument, NULL, 's' },
	{ "grid", required_argument, NULL, 'g' },
	{ "state", required_argument, NULL, 'd' },
	{ "out", required_argument, NULL, 'o' },
	{ "plot", required_argument, NULL, 'P' },
	{ "angles", required_argument, NULL, 'a' },
	{ "alpha-at", required_argument, NULL, 'A' },
	TRACE_RUN_LONG_OPTIONS,
	{ "lens", required_argument, NULL, 'l' },
	{ "set", required_argument, NULL, 'S' },
	{ "json", no_argument, NULL, 'j' },
	{ "help", no_argument, NULL, 'h' },
	SENSOR_LONG_OPTIONS,
	NORMALISATION_LONG_OPTION,
	DETECTOR_LONG_OPTIONS,
	{ NULL, 0, NULL, 0 }
};

/* Numbers and strings; 1 when opt is neither. */
static int parse_value(int opt, char *arg, struct sweep_args *a, int *rc)
{
	switch (opt) {
	case 's': a->job.scene = arg; return 0;
	case 'd': a->job.state = arg; return 0;
	case 'o': a->out = arg; return 0;
	case 'P': a->plot = arg; return 0;
	case 'a': a->job.angles = arg; return 0;
	case 'A': a->job.at_list = arg; return 0;
	case 'l': a->job.lens = arg; return 0;
	case 'j': cli.json = 1; return 0;
	default: return trace_run_option("sweep", opt, arg, &a->job.o, rc);
	}
}

static int parse_args(int argc, char **argv, struct sweep_args *a,
		      struct fdr_setup *fs)
{
	struct stray_error err;
	int opt, rc = CLI_OK, h;

	opterr = 0;
	stray_error_clear(&err);
	while (!rc && (opt = getopt_long(argc, argv, "h", sweep_opts,
					 NULL)) != -1) {
		if (!parse_value(opt, optarg, a, &rc))
			continue;
		if (opt == 'h') {
			fputs(usage, stdout);
			return -1;
		} else if (opt == 'g') {
			if (design_grid_add(&a->job.grid, optarg, &err))
				return cli_fail("sweep", &err);
		} else if (opt == 'S' && a->job.n_sets < DESIGN_SWEEP_SETS_MAX) {
			a->job.sets[a->job.n_sets++] = optarg;
		} else if ((h = fdr_setup_option(fs, "sweep", opt, optarg))) {
			rc = h == 1 ? CLI_OK : h;
		} else {
			return cli_usage_error("sweep", "unknown option '%s'",
					       argv[optind - 1]);
		}
	}
	if (!rc && optind < argc)
		rc = cli_usage_error("sweep", "unexpected argument '%s'",
				     argv[optind]);
	if (!rc && (!a->job.scene || !a->job.state || a->job.grid.n_axes == 0))
		rc = cli_usage_error("sweep", "--scene, --state and at least "
				     "one --grid are required");
	if (!rc && a->job.n_sets + a->job.grid.n_axes > DESIGN_SWEEP_SETS_MAX)
		rc = cli_usage_error("sweep", "too many --set and --grid");
	return rc;
}

/* Report the designs as they are traced or taken back. */
static void progress(void *user, size_t i, size_t n,
		     const struct design_result *d)
{
	(void)user;
	fprintf(stderr, "stray sweep: design %zu/%zu %s: %s\n", i + 1, n,
		d->label, d->resumed ? "kept" : "traced");
}

static int sweep(struct sweep_args *a, struct fdr_setup *fs,
		 struct stray_error *err)
{
	struct stray_fdr_model m;
	double alpha_req = NAN;
	struct stray_detector_req req;
	int rc = fdr_setup_load(fs, err);

	req.binding = STRAY_FAIL_FALSE_STARS;
	if (!rc) {
		/* the detector's answer, both failure modes (thesis: eq. 2.18) */
		fdr_setup_model(fs, fs->flux.sun, &m);
		rc = fdr_setup_alpha_required(fs, &m, &req, err);
		alpha_req = req.alpha_req;
	}
	a->job.progress = progress;
	if (!rc)
		rc = design_sweep_run(&a->job, alpha_req, err);
	if (!rc) {
		struct sweep_summary s = { a->job.d, a->job.grid.n_designs,
			a->job.at, a->job.n_at, alpha_req, fs->sensor_spec ?
			fs->sensor_spec : "st16-like",
			stray_normalisation_name(fs->normalisation),
			fdr_setup_k_px(fs), stray_detector_name(fs->detector),
			stray_failure_mode_name(req.binding) };

		stray_file_defer();	/* the table and its plot, or neither */
		if (a->out)
			rc = design_write_csv(&s, a->out, err);
		if (!rc && a->plot)
			rc = design_plot(&s, a->plot, err);
		if (stray_file_finish(!rc, err) != STRAY_OK && !rc)
			rc = STRAY_EIO;
		if (!rc && cli.json)
			rc = design_print_json(&s) ? STRAY_EIO : STRAY_OK;
		else if (!rc)
			design_print_text(&s);
	}
	design_sweep_free(&a->job);
	return rc;
}

int cmd_sweep(int argc, char **argv, const struct tracer_runner *runner)
{
	struct sweep_args a;
	struct fdr_setup fs;
	struct stray_error err;
	int rc;

	memset(&a, 0, sizeof(a));
	a.job.runner = runner;
	trace_run_defaults(&a.job.o, 300000);
	fdr_setup_init(&fs);
	rc = parse_args(argc, argv, &a, &fs);
	if (rc)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	rc = sweep(&a, &fs, &err);
	return rc ? cli_fail("sweep", &err) : CLI_OK;
}
