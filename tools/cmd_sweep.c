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

#define SETS_MAX 64

struct sweep_args {
	const struct tracer_runner *runner;	/* who runs the traces */
	const char *scene, *angles, *lens, *state, *out, *plot, *at_list;
	const char *sets[SETS_MAX];
	int n_sets;
	struct design_grid grid;
	struct tracer_trace_opts o;
	double at[SWEEP_AT_MAX];
	int n_at;
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
	case 's': a->scene = arg; return 0;
	case 'd': a->state = arg; return 0;
	case 'o': a->out = arg; return 0;
	case 'P': a->plot = arg; return 0;
	case 'a': a->angles = arg; return 0;
	case 'A': a->at_list = arg; return 0;
	case 'l': a->lens = arg; return 0;
	case 'j': cli.json = 1; return 0;
	default: return trace_run_option("sweep", opt, arg, &a->o, rc);
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
			if (design_grid_add(&a->grid, optarg, &err))
				return cli_fail("sweep", &err);
		} else if (opt == 'S' && a->n_sets < SETS_MAX) {
			a->sets[a->n_sets++] = optarg;
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
	if (!rc && (!a->scene || !a->state || a->grid.n_axes == 0))
		rc = cli_usage_error("sweep", "--scene, --state and at least "
				     "one --grid are required");
	if (!rc && a->n_sets + a->grid.n_axes > SETS_MAX)
		rc = cli_usage_error("sweep", "too many --set and --grid");
	return rc;
}

/* The traced angles, with 0 first (alpha is normalised to P(0)). */
/* A scene parameter from a --grid axis is refused by the scene loader as
 * a --set; name the option the user gave. */
static void blame_grid(const struct sweep_args *a, struct stray_error *err)
{
	int k;

	if (!err || !err->field || strcmp(err->field, "--set") != 0)
		return;
	for (k = 0; k < a->grid.n_axes; k++)
		if (strcmp(err->text, a->grid.axis[k].key) == 0)
			err->field = "--grid";
}

static int make_angles(struct sweep_args *a, double **theta, size_t *n,
		       struct stray_error *err)
{
	double *at = NULL, *t;
	size_t n_at = 0, i;
	int rc = tracer_angles_parse(a->angles ? a->angles : "0:30:5,30:90:1",
				     theta, n, err);

	if (!rc) {
		rc = tracer_angles_parse(a->at_list ? a->at_list : "20,30,40",
					 &at, &n_at, err);
		if (rc && err)		/* the parser speaks of --angles */
			err->field = "--alpha-at";
	}
	if (!rc && n_at > SWEEP_AT_MAX)
		rc = stray_error_set_value(err, STRAY_EINVAL, "--alpha-at",
					   "at most 16 angles", (double)n_at);
	for (i = 0; !rc && i < n_at; i++)
		a->at[i] = at[i];
	a->n_at = (int)n_at;
	free(at);
	if (rc || (*theta)[0] == 0.0)
		return rc;
	t = realloc(*theta, (*n + 1) * sizeof(double));
	if (!t)
		return stray_error_set(err, STRAY_ENOMEM, "--angles",
				       "out of memory");
	memmove(t + 1, t, *n * sizeof(double));
	t[0] = 0.0;
	*theta = t;
	(*n)++;
	return STRAY_OK;
}

/* What must match for a kept curve to stand for this run's design. */
static void run_key(const struct sweep_args *a, const char *label,
		    char *buf, size_t size)
{
	snprintf(buf, size, "%s | scene %s | rays %llu seed %llu batches %d"
		 " | angles %s | lens %s", label, a->scene,
		 (unsigned long long)a->o.n_paths,
		 (unsigned long long)a->o.seed, a->o.n_batches,
		 a->angles ? a->angles : "default", a->lens ? a->lens : "none");
}

/* A kept curve with this key, or 0 (absent, other run, unreadable). */
static int resume(const char *path, const char *key, struct stray_curve *c)
{
	struct stray_error err;
	char want[1200];
	size_t i;

	if (access(path, F_OK) != 0)
		return 0;
	stray_error_clear(&err);
	if (stray_curve_load(path, c, &err)) {
		stray_file_forget_input(path);	/* broken: traced anew */
		return 0;
	}
	snprintf(want, sizeof(want), " sweep_run: %s", key);
	for (i = 0; i < c->n_meta; i++)
		if (strcmp(c->meta[i], want) == 0)
			return 1;
	stray_curve_free(c);
	stray_file_forget_input(path);	/* another run's: traced anew */
	return 0;
}

/* Trace one design and keep its curve (alpha, sigma from theta > 0). */
static int trace_design(const struct sweep_args *a, const char *const *sets,
			int n_sets, const struct tracer_lens *lens,
			const char *key, const char *path,
			struct stray_curve *c, struct stray_error *err)
{
	struct tracer_scene_spec spec = { a->scene, sets, n_sets, a->lens,
					  0.0, 0.0 };
	struct tracer_trace_opts o = a->o;
	struct tracer_scene s;
	struct tracer_result r;
	size_t j, n = a->o.n_theta - 1;
	int rc;

	o.lens = a->lens ? lens : NULL;
	tracer_scene_init(&s);
	rc = tracer_scene_load(a->scene, sets, n_sets, &s, err);
	if (!rc)
		rc = tracer_scene_commit(&s, err);
	if (!rc)
		rc = tracer_run(a->runner, &spec, &s, &o, &r, err);
	tracer_scene_free(&s);
	if (rc)
		return rc;
	{	/* alpha = P(theta) / P(0): refuse 0/0 (a blocked beam) */
		double p0, s0;

		tracer_result_power(&r, 0, -1, &p0, &s0);
		if (!(p0 > 0.0)) {
			tracer_result_free(&r);
			stray_error_at(err, STRAY_EINVAL, a->scene, 0, "beam",
				"no on-axis power reaches the detector in this "
				"design (is the beam blocked?): alpha would be 0/0");
			stray_error_text(err, key);
			return STRAY_EINVAL;
		}
	}
	rc = stray_curve_alloc(c, n, 1, err);
	for (j = 0; !rc && j < n; j++) {
		c->theta_deg[j] = o.theta_deg[j + 1];
		tracer_result_alpha(&r, j + 1, 0, -1, &c->alpha[j],
				    &c->sigma[j]);
	}
	tracer_result_free(&r);
	if (!rc)
		rc = stray_curve_add_meta(c, "kind", "baffle", err);
	if (!rc)
		rc = stray_curve_add_meta(c, "sweep_run", key, err);
	if (!rc)
		rc = stray_curve_save(path, c, err);
	stray_curve_free(c);
	/* judged as read back, so a resumed sweep gives the same bytes */
	return rc ? rc : stray_curve_load(path, c, err);
}

/* Sun exclusion angle and alpha at the chosen angles of one curve. */
static int judge(const struct sweep_args *a, const struct stray_curve *c,
		 double alpha_req, struct design_result *d,
		 struct stray_error *err)
{
	struct stray_curve_view v = stray_curve_view_of(c);
	struct stray_exclusion ex;
	/* libstray's one verdict: NaN (JSON null) where not excluded */
	int k, rc = stray_exclusion_interval(&v, alpha_req, 1.0, &ex, err);

	if (rc != STRAY_OK)
		return rc;
	d->sun_deg = ex.theta_deg;
	d->sun_lo_deg = ex.excluded ? ex.theta_lo_deg : NAN;
	d->sun_hi_deg = ex.hi_reached ? ex.theta_hi_deg : NAN;
	for (k = 0; k < a->n_at; k++)
		d->alpha_at[k] = stray_curve_alpha_at(&v, a->at[k]);
	return rc;
}

static int make_state_dir(const char *dir, struct stray_error *err)
{
	if (mkdir(dir, 0777) == 0 || errno == EEXIST)
		return STRAY_OK;
	stray_error_set(err, STRAY_EIO, "--state", "cannot create folder");
	stray_error_text(err, dir);
	return STRAY_EIO;
}

static int run_design(const struct sweep_args *a, size_t i,
		      const struct tracer_lens *lens, double alpha_req,
		      struct design_result *d, struct stray_error *err)
{
	char set[GRID_AXES_MAX][2 * GRID_TEXT_MAX], key[1100], path[4200];
	const char *sets[SETS_MAX];
	struct stray_curve c;
	int k, n = a->n_sets, rc = STRAY_OK;

	design_grid_sets(&a->grid, i, set);
	design_grid_label(&a->grid, i, d->label, sizeof(d->label));
	for (k = 0; k < n; k++)
		sets[k] = a->sets[k];
	for (k = 0; k < a->grid.n_axes; k++)
		sets[n++] = set[k];
	run_key(a, d->label, key, sizeof(key));
	snprintf(path, sizeof(path), "%s/design_%04zu.csv", a->state, i);
	d->resumed = resume(path, key, &c);
	if (!d->resumed)
		rc = trace_design(a, sets, n, lens, key, path, &c, err);
	if (rc)
		return rc;
	fprintf(stderr, "stray sweep: design %zu/%zu %s: %s\n", i + 1,
		a->grid.n_designs, d->label, d->resumed ? "kept" : "traced");
	rc = judge(a, &c, alpha_req, d, err);
	stray_curve_free(&c);
	return rc;
}

static int sweep(struct sweep_args *a, struct fdr_setup *fs,
		 struct stray_error *err)
{
	struct tracer_lens lens = { 0, NULL, NULL };
	struct design_result *d;
	struct stray_fdr_model m;
	double *theta = NULL, alpha_req = NAN;
	struct stray_detector_req req;
	size_t n, i;
	int rc = fdr_setup_load(fs, err);

	req.binding = STRAY_FAIL_FALSE_STARS;
	if (!rc) {
		/* the detector's answer, both failure modes (thesis: eq. 2.18) */
		fdr_setup_model(fs, fs->flux.sun, &m);
		rc = fdr_setup_alpha_required(fs, &m, &req, err);
		alpha_req = req.alpha_req;
	}
	if (!rc)
		rc = make_angles(a, &theta, &n, err);
	if (!rc && a->lens)
		rc = tracer_lens_load(a->lens, &lens, err);
	if (!rc)
		rc = make_state_dir(a->state, err);
	d = calloc(a->grid.n_designs, sizeof(*d));
	if (!rc && !d)
		rc = stray_error_set(err, STRAY_ENOMEM, "sweep", "out of memory");
	a->o.theta_deg = theta;
	a->o.n_theta = n;
	for (i = 0; !rc && i < a->grid.n_designs; i++)
		rc = run_design(a, i, &lens, alpha_req, &d[i], err);
	blame_grid(a, err);
	if (!rc) {
		struct sweep_summary s = { d, a->grid.n_designs, a->at,
			a->n_at, alpha_req, fs->sensor_spec ?
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
	free(d);
	free(theta);
	tracer_lens_free(&lens);
	return rc;
}

int cmd_sweep(int argc, char **argv, const struct tracer_runner *runner)
{
	struct sweep_args a;
	struct fdr_setup fs;
	struct stray_error err;
	int rc;

	memset(&a, 0, sizeof(a));
	a.runner = runner;
	trace_run_defaults(&a.o, 300000);
	fdr_setup_init(&fs);
	rc = parse_args(argc, argv, &a, &fs);
	if (rc)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	rc = sweep(&a, &fs, &err);
	return rc ? cli_fail("sweep", &err) : CLI_OK;
}
