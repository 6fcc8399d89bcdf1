/*
 * cmd_trace.c - `stray trace`: the attenuation curve of a baffle scene by
 * Monte Carlo ray tracing (thesis §3.4), the scatter-order breakdown
 * (fig. 5.5) and the top stray-light paths (§5.3).
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "cli_capture.h"
#include "commands.h"
#include "plot.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"
#include "tracer/angles.h"
#include "tracer/baffle.h"
#include "tracer/dump_io.h"
#include "tracer/integrator.h"
#include "tracer/obj_export.h"
#include "tracer/path_report.h"
#include "tracer/runner.h"
#include "tracer/spectral.h"
#include "tracer/trace_job.h"
#include "tracer/scene_load.h"
#include "trace_focal.h"
#include "trace_run.h"

static const char usage[] =
	"usage: stray trace --scene SCENE [--angles LIST] [--out C.csv]\n"
	"                   [--rays N] [--seed K] [--threads T] [--lens L.csv]\n"
	"                   [--set key=value]... [--export-obj M.obj]\n"
	"                   [--paths-out P.csv] [--top N] [--plot F.png]\n"
	"                   [--plot-orders F.png] [--dump-paths D.csv]\n"
	"                   [--map M.csv --map-angle DEG] [--json]\n"
	"                   [--focal-map M.fits] [--focal-map-png P.png]\n"
	"\n"
	"Attenuation curve alpha(theta) = P_det(theta) / P_det(0) of a scene\n"
	"under a collimated beam, by adjoint Monte Carlo with next-event\n"
	"connections to the source (one set of paths serves every angle).\n"
	"\n"
	"  --scene SCENE     'ref4' (built in) or a scene file (JSON: meshes,\n"
	"                    or \"type\": \"vanes\", the vane family)\n"
	"  --angles LIST     e.g. 0,5,10:30:0.5; default 'auto': 1 deg steps,\n"
	"                    0.1 deg within 1 deg of the scene's direct\n"
	"                    cut-off (found by shadow rays), 0.5 deg beyond\n"
	"  --out C.csv       curve with sigma and direct/order1/order2/order3plus\n"
	"  --rays N          detector-side paths (default 1500000)\n"
	"  --seed K          random seed (default 1); same seed, same output\n"
	"  --threads T       worker threads (default: online CPUs)\n"
	"  --batches B       independent batches for sigma (default 64)\n"
	"  --light-paths     add light-side single-scatter samples where the\n"
	"                    pilot finds they pay (MIS; grazing angles; the\n"
	"                    default)\n"
	"  --no-light-paths  detector-side paths alone (the old estimator)\n"
	"  --lens L.csv      lens transmission vs incidence (curve CSV)\n"
	"  --set key=value   override a scene parameter (repeatable; keys\n"
	"                    below, units and limits in docs/scene.md)\n"
	"  --export-obj M    write the scene mesh, one group per surface\n"
	"  --paths-out P.csv per-angle power by surface-group sequence\n"
	"  --top N           print the N strongest paths per angle\n"
	"  --plot F.png      the curve with its error bars (log alpha)\n"
	"  --plot-orders F   alpha by scatter order (thesis fig. 5.5)\n"
	"  --dump-paths D    vertices of sample paths (fig. 5.6)\n"
	"  --dump-count N    how many paths to dump (default 100)\n"
	"  --map M.csv       detector irradiance map at --map-angle\n"
	"  --map-size N      map pixels per side (default 64)\n"
	"  --spectrum S      source spectrum for materials with a\n"
	"                    \"reflectance_table\" (CSV or builtin:NAME;\n"
	"                    default builtin:sun_am0_astm_e490)\n"
	"  --response R      detector response for them (a photometer's own;\n"
	"                    default builtin:qe_mt9p031_approx)\n"
	FOCAL_MAP_USAGE
	"  --json            print a run summary (paths_per_s, ...)\n"
	"\n"
	"--set keys of ref4 and vane scenes (\"type\": \"vanes\"; mm, deg):\n"
	TRACER_BAFFLE_KEYS "\n"
	"--set keys of mesh scenes: accept_half_angle_deg edge_radius\n";

/* The command line: the trace job (tracer/trace_job.h) and what only the
 * command writes and prints. */
struct trace_args {
	struct tracer_job job;
	const char *out, *export_obj, *paths_out;
	const char *plot, *plot_orders, *dump, *map;
	double map_angle;
	int dump_count, map_size;
	int top;
	struct focal_map_args fm;	/* --focal-map (trace_focal.h) */
};

static const struct option trace_opts[] = {
	{ "scene", required_argument, NULL, 's' },
	{ "angles", required_argument, NULL, 'a' },
	{ "out", required_argument, NULL, 'o' },
	TRACE_RUN_LONG_OPTIONS,
	{ "lens", required_argument, NULL, 'l' },
	{ "set", required_argument, NULL, 'S' },
	{ "export-obj", required_argument, NULL, 'x' },
	{ "paths-out", required_argument, NULL, 'p' },
	{ "top", required_argument, NULL, 'T' },
	{ "plot", required_argument, NULL, 'P' },
	{ "plot-orders", required_argument, NULL, 'O' },
	{ "dump-paths", required_argument, NULL, 'D' },
	{ "dump-count", required_argument, NULL, 'C' },
	{ "map", required_argument, NULL, 'M' },
	{ "map-angle", required_argument, NULL, 'A' },
	{ "map-size", required_argument, NULL, 'Z' },
	{ "spectrum", required_argument, NULL, 1001 },
	{ "response", required_argument, NULL, 1002 },
	{ "light-paths", no_argument, NULL, 1003 },
	{ "no-light-paths", no_argument, NULL, 1004 },
	FOCAL_MAP_LONG_OPTIONS,
	{ "json", no_argument, NULL, 'j' },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 }
};

/* The numeric options; 1 when opt is not one of them. */
static int parse_number(int opt, const char *text, struct trace_args *a,
			int *rc)
{
	double v = 0.0;

	switch (opt) {
	case 'A':
		*rc = cli_parse_double("trace", "map-angle", text,
				       &a->map_angle);
		return 0;
	case 'C': *rc = cli_parse_count("trace", "dump-count", text, 1, 1e6, &v);
		a->dump_count = (int)v; return 0;
	case 'Z': *rc = cli_parse_count("trace", "map-size", text, 1, 4096, &v);
		a->map_size = (int)v; return 0;
	case 'T': *rc = cli_parse_count("trace", "top", text, 1, 1000, &v);
		a->top = (int)v; return 0;
	case 1003: case 1004:	/* strategy B (tracer/light.h) */
		a->job.o.light_paths = opt == 1003;
		return 0;
	default:
		return trace_run_option("trace", opt, text, &a->job.o, rc);
	}
}

/* The file options; 1 when opt is not one of them. */
static int parse_file(int opt, char *text, struct trace_args *a)
{
	switch (opt) {
	case 's': a->job.scene = text; return 0;
	case 'a': a->job.angles = text; return 0;
	case 'o': a->out = text; return 0;
	case 'l': a->job.lens = text; return 0;
	case 'x': a->export_obj = text; return 0;
	case 'p': a->paths_out = text; return 0;
	case 'P': a->plot = text; return 0;
	case 'O': a->plot_orders = text; return 0;
	case 'D': a->dump = text; return 0;
	case 'M': a->map = text; return 0;
	case 1001: a->job.spectrum = text; return 0;
	case 1002: a->job.response = text; return 0;
	default: return 1;
	}
}

static int parse_args(int argc, char **argv, struct trace_args *a)
{
	int opt, rc = CLI_OK;

	opterr = 0;	/* one line of our own instead of getopt's */
	while (!rc && (opt = getopt_long(argc, argv, "h", trace_opts,
					 NULL)) != -1) {
		if (!parse_file(opt, optarg, a) ||
		    !focal_map_option(opt, optarg, &a->fm, &rc) ||
		    !parse_number(opt, optarg, a, &rc))
			continue;
		if (opt == 'j') {
			cli.json = 1;
		} else if (opt == 'S' && a->job.n_sets < TRACER_JOB_SETS_MAX) {
			a->job.sets[a->job.n_sets++] = optarg;
		} else if (opt == 'S') {
			return cli_usage_error("trace", "too many --set");
		} else if (opt == 'h') {
			fputs(usage, stdout);
			return -1;
		} else {
			return cli_usage_error("trace", "unknown option '%s'",
					       argv[optind - 1]);
		}
	}
	if (!rc && optind < argc)
		rc = cli_usage_error("trace", "unexpected argument '%s'",
				     argv[optind]);
	if (!rc && !a->job.scene)
		rc = cli_usage_error("trace", "--scene is required");
	if (!rc && !a->out && !a->export_obj && !cli.json && !a->plot &&
	    !a->plot_orders && !a->paths_out && !a->top && !a->dump &&
	    !a->map && !focal_map_wanted(&a->fm))
		rc = cli_usage_error("trace", "nothing to do: give --out, "
				     "--export-obj or --json");
	return rc;
}

static void progress(void *user, double fraction)
{
	int *last = user, pct = (int)(100.0 * fraction);

	if (pct / 10 != *last / 10 || pct == 100) {
		fprintf(stderr, "\rstray trace: %3d%%", pct);
		if (pct == 100)
			fputc('\n', stderr);
		*last = pct;
	}
}

static cJSON *summary_json(const struct trace_args *a,
			   const struct tracer_result *r, size_t first)
{
	cJSON *o = cJSON_CreateObject();
	double worst = 0.0, al, sg;
	size_t j;

	for (j = first; j < r->n_theta; j++) {
		tracer_result_alpha(r, j, 0, -1, &al, &sg);
		if (al > 0.0 && sg / al > worst)
			worst = sg / al;
	}
	cJSON_AddStringToObject(o, "scene", a->job.scene);
	cJSON_AddNumberToObject(o, "angles", (double)(r->n_theta - first));
	if (a->job.auto_angles)
		cJSON_AddNumberToObject(o, "direct_cutoff_deg",
					a->job.cutoff_deg);
	cJSON_AddNumberToObject(o, "paths", (double)r->n_paths);
	cJSON_AddNumberToObject(o, "threads", a->job.o.threads);
	if (a->job.o.light_paths)	/* absent when off: the old summary */
		cJSON_AddBoolToObject(o, "light_paths", 1);
	cJSON_AddItemToObject(o, "seconds", cli_json_number(r->seconds));
	cJSON_AddItemToObject(o, "paths_per_s",
			      cli_json_number(r->n_paths / r->seconds));
	cJSON_AddItemToObject(o, "casts_per_s",
			      cli_json_number(r->casts / r->seconds));
	cJSON_AddNumberToObject(o, "casts", (double)r->casts);
	cJSON_AddNumberToObject(o, "connections", (double)r->connections);
	cJSON_AddItemToObject(o, "worst_rel_sigma", cli_json_number(worst));
	if (a->out)
		cJSON_AddStringToObject(o, "out", a->out);
	focal_map_json(&a->fm, o);
	return o;
}

/* Error bars of alpha +- sigma, or the orders, as PNG (log alpha). */
static int plot_curve(const struct trace_args *a,
		      const struct tracer_result *r, size_t first,
		      struct stray_error *err)
{
	static const enum plot_color col[TRACER_ORDERS] = {
		PLOT_BLACK, PLOT_BLUE, PLOT_RED, PLOT_GREEN
	};
	size_t n = r->n_theta - first, j;
	double *buf = malloc(7 * n * sizeof(double)), s;
	double *al = buf + n, *lo = buf + 2 * n, *hi = buf + 3 * n;
	struct plot_series ser[TRACER_ORDERS];
	struct plot_spec sp = { a->plot, "stray trace: attenuation curve",
				"theta (deg)", "alpha", 0, 1, NAN, NAN, NAN,
				NAN, ser, 1, 0 };
	int k, rc = STRAY_OK;

	if (!buf)
		return stray_error_set(err, STRAY_ENOMEM, "--plot",
				       "out of memory");
	memset(ser, 0, sizeof(ser));
	for (j = 0; j < n; j++) {
		buf[j] = r->theta_deg[first + j];
		tracer_result_alpha(r, first + j, 0, -1, &al[j], &s);
		lo[j] = al[j] - s;
		hi[j] = al[j] + s;
	}
	ser[0] = (struct plot_series){ buf, al, n, lo, hi, PLOT_BLACK,
				       PLOT_LINE, "alpha +- sigma" };
	if (a->plot)
		rc = plot_render(&sp, err);
	for (k = 0; k < TRACER_ORDERS && !rc && a->plot_orders; k++) {
		double *y = k == 0 ? lo : k == 1 ? hi : k == 2 ? buf + 4 * n :
			    buf + 5 * n;

		for (j = 0; j < n; j++)
			tracer_result_alpha(r, first + j, 0, k, &y[j], &s);
		ser[k] = (struct plot_series){ buf, y, n, NULL, NULL, col[k],
			PLOT_LINE, tracer_order_names[k] };
	}
	if (!rc && a->plot_orders) {
		sp.path = a->plot_orders;
		sp.title = "stray trace: alpha by scatter order";
		sp.n_series = TRACER_ORDERS;
		rc = plot_render(&sp, err);
	}
	free(buf);
	return rc;
}

static int load_scene(const struct trace_args *a, struct tracer_scene *s,
		      struct stray_error *err)
{
	int rc = tracer_scene_load(a->job.scene, a->job.sets, a->job.n_sets,
				   s, err);

	if (!rc && a->export_obj)
		rc = tracer_obj_export(&s->mesh, a->export_obj, err);
	return rc;
}

static int run_trace(struct trace_args *a, struct tracer_scene *s,
		     struct stray_error *err)
{
	struct tracer_job *j = &a->job;
	struct tracer_result r;
	size_t first;
	int rc, last = -1;

	j->o.record_paths = a->paths_out || a->top;
	rc = tracer_job_prepare(j, s, err);
	if (rc)
		return rc;
	first = j->first;
	if (a->dump)
		j->o.dump_paths = (uint64_t)a->dump_count <= j->o.n_paths ?
				  (uint64_t)a->dump_count : j->o.n_paths;
	if (a->map) {
		rc = tracer_job_angle_index(j, a->map_angle,
					    &j->o.map_theta_index, err);
		j->o.map_n = a->map_size;
		if (rc)
			return rc;
	}
	if (focal_map_wanted(&a->fm)) {
		size_t k;

		rc = tracer_job_angle_index(j, a->map_angle, &k, err);
		if (!rc)
			rc = focal_map_prepare(&a->fm, k, &j->o, err);
		if (rc)
			return rc;
	}
	if (isatty(STDERR_FILENO) && !cli_capturing()) {
		j->o.progress = progress;
		j->o.progress_user = &last;
	}
	rc = tracer_job_run(j, s, &r, err);
	if (rc)
		return rc;
	if (a->out || cli_capturing()) {	/* a library call keeps the bits */
		struct stray_curve c;

		rc = tracer_job_curve(j, &r, &c, err);
		if (!rc) {
			rc = cli_capture_curve(&c, err);
			if (!rc && a->out)
				rc = stray_curve_save(a->out, &c, err);
			stray_curve_free(&c);
		}
	}
	if (!rc && (a->plot || a->plot_orders))
		rc = plot_curve(a, &r, first, err);
	if (!rc && a->paths_out)
		rc = tracer_paths_write_csv(&r, s, a->paths_out, err);
	if (!rc && a->dump)
		rc = tracer_dump_write_csv(&r, s, a->dump, err);
	if (!rc && a->map)
		rc = tracer_map_write_csv(&r, a->map, err);
	if (!rc && focal_map_wanted(&a->fm))
		rc = focal_map_write(&a->fm, &r, s, &j->o, err);
	if (!rc && a->top && !cli.json)
		tracer_paths_print_top(&r, s, first, a->top, stdout);
	if (!rc && cli.json)
		rc = cli_json_emit(summary_json(a, &r, first));
	tracer_result_free(&r);
	return rc;
}

int cmd_trace(int argc, char **argv, const struct tracer_runner *runner)
{
	struct trace_args a;
	struct tracer_scene s;
	struct stray_error err;
	int rc;

	memset(&a, 0, sizeof(a));
	a.job.runner = runner;
	trace_run_defaults(&a.job.o, 1500000);	/* about 1 % at every angle */
	/* strategy B on for this command only (issue 27: the grazing angles'
	 * error halved for 17-37 % more CPU, tracer/README.md); sweep,
	 * diagnose and the library keep the detector-side estimator */
	a.job.o.light_paths = 1;
	a.dump_count = 100;
	a.map_size = 64;
	focal_map_defaults(&a.fm);
	rc = parse_args(argc, argv, &a);
	if (rc)
		return rc < 0 ? CLI_OK : rc;
	a.job.auto_angles = !a.job.angles || strcmp(a.job.angles, "auto") == 0;
	stray_error_clear(&err);
	tracer_scene_init(&s);
	stray_file_defer();	/* every output renamed at the end, or none */
	rc = load_scene(&a, &s, &err);
	if (!rc && s.note[0]) {	/* a CAD mesh put right: say what */
		cli_note("trace", "%s: %s", a.job.scene, s.note);
		a.job.scene_note = s.note;
	}
	if (!rc && (a.out || cli.json || a.paths_out || a.top || a.plot ||
		    a.plot_orders || a.dump || a.map ||
		    focal_map_wanted(&a.fm)))
		rc = run_trace(&a, &s, &err);
	tracer_job_free(&a.job);
	tracer_scene_free(&s);
	if (stray_file_finish(rc == STRAY_OK, &err) != STRAY_OK && !rc)
		rc = STRAY_EIO;
	return rc ? cli_fail("trace", &err) : CLI_OK;
}
