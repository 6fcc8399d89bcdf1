/*
 * cmd_diagnose.c - `stray diagnose MEASURED.csv --scene SCENE`: what the
 * simulation gets wrong against a measured curve, which registered
 * physical cause explains it, and the gain (issue 5; thesis §4).
 * The work is the diagnose/ library (diagnose/diag_result.h); here the
 * options, and the report in words, JSON and plots (diag_report.h).
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "diag_report.h"
#include "diagnose/diag_spectral.h"
#include "stray/errfmt.h"
#include "stray/detector.h"
#include "stray/sensor_io.h"

static const char usage[] =
	"usage: stray diagnose MEASURED.csv --scene SCENE [--rays N]\n"
	"                      [--seed K] [--threads T] [--set key=value]...\n"
	"                      [--spectrum S] [--response R]\n"
	"                      [--plot F.png] [--causes [a,b]] [--without a,b]\n"
	"                      [--sensor S] [--json]\n"
	"                      [--lens L.csv] [--surfaces] [--write-model M.json]\n"
	"\n"
	"Compares a measured attenuation curve (CSV with a sigma column) with\n"
	"the traced model of SCENE, fits each registered physical cause and\n"
	"greedy combinations by weighted least squares of log10 residuals,\n"
	"names the causes that lower BIC by more than 10, with profile-chi2\n"
	"intervals, and reports the gain and the Sun exclusion angle before\n"
	"and after.\n"
	"\n"
	"  --scene SCENE     'ref4' (built in) or a scene file\n"
	"  --rays N          detector-side paths per trace (default 200000)\n"
	"  --seed K          seed shared by every trace (default 1)\n"
	"  --threads T       tracer threads (default 1)\n"
	"  --set key=value   the scene as built (repeatable)\n"
	"  --spectrum S      the source's spectrum, CSV or builtin:NAME, for a\n"
	"                    coating that changes with wavelength (default\n"
	"                    builtin:sun_am0_astm_e490)\n"
	"  --response R      the detector's spectral response (a photometer's\n"
	"                    own; default builtin:qe_mt9p031_approx)\n"
	"  --plot F.png      measured vs model (F.png) and residuals (F-resid.png)\n"
	"  --lens L.csv      a system curve (baffle + lens): the trace includes\n"
	"                    the lens table, as `stray trace --lens`; lens causes\n"
	"                    (lens_scale, lens_ghost) join the registry\n"
	"  --surfaces        localise per surface group (reflectance / ABg scale\n"
	"                    factors by re-weighting the path table, few groups,\n"
	"                    BIC) even when the registry explains the curve\n"
	"                    (it runs anyway when a significant residual is left)\n"
	"  --write-model M.json  the extended model as a scene file (and M.obj),\n"
	"                    for `stray trace --scene M.json`\n"
	"  --causes a,b      fit only these causes (alone: list the registered\n"
	"                    causes and exit)\n"
	"  --without a,b     fit every cause but these\n"
	"  --sensor S        the sensor of the Sun exclusion angle (a name or\n"
	"                    JSON file; default st16-like)\n"
	"  (a theta 0 row of alpha 1 and sigma 0, as `stray trace` writes it,\n"
	"  normalises the curve and is kept out of the fit; each cause's\n"
	"  range and nominal value are the scene's own)\n"
	"  --detector D      the tracker's detector of that angle: thesis (eq.\n"
	"                    2.18, default), window, threshold or tetra3, whose\n"
	"                    false stars and lost stars both bind; default: the\n"
	"                    sensor file's (docs/detectors.md)\n"
	"  --detector-sigma K  tetra3's threshold in frame sigmas (3)\n"
	"  --json            machine-readable output\n";

struct diag_args {
	const char *measured, *scene, *plot, *spectrum, *response, *lens;
	const char *model, *only, *without, *sensor, *detector;
	double detector_sigma;
	const char *sets[DIAG_SETS_MAX];
	int n_sets, list, surfaces;
	double rays, seed, threads;
};

static int parse_args(int argc, char **argv, struct diag_args *a)
{
	static const struct option opts[] = {
		{ "scene", required_argument, NULL, 's' },
		{ "rays", required_argument, NULL, 'n' },
		{ "seed", required_argument, NULL, 'k' },
		{ "threads", required_argument, NULL, 't' },
		{ "set", required_argument, NULL, 'S' },
		{ "plot", required_argument, NULL, 'p' },
		{ "spectrum", required_argument, NULL, 'Q' },
		{ "response", required_argument, NULL, 'R' },
		{ "causes", optional_argument, NULL, 'c' },
		{ "without", required_argument, NULL, 'w' },
		{ "sensor", required_argument, NULL, 'X' },
		{ "lens", required_argument, NULL, 'L' },
		{ "surfaces", no_argument, NULL, 'G' },
		{ "write-model", required_argument, NULL, 'W' },
		{ "detector", required_argument, NULL, 'd' + 256 },
		{ "detector-sigma", required_argument, NULL, 'D' + 256 },
		{ "json", no_argument, NULL, 'j' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc = CLI_OK;
	char bad[128];

	while (!rc && (opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 's': a->scene = optarg; break;
		case 'p': a->plot = optarg; break;
		case 'Q': a->spectrum = optarg; break;
		case 'R': a->response = optarg; break;
		case 'c':	/* `--causes a,b` or `--causes=a,b`; alone: list */
			if (!optarg && optind < argc &&
			    !diag_causes_check(argv[optind], bad, sizeof(bad)))
				optarg = argv[optind++];
			if (!optarg)
				a->list = 1;
			else if (diag_causes_check(optarg, bad, sizeof(bad)))
				return cli_usage_error("diagnose", "option "
					"'--causes': '%s' is not a registered "
					"cause (stray diagnose --causes lists "
					"them)", bad);
			else
				a->only = optarg;
			break;
		case 'w':
			if (diag_causes_check(optarg, bad, sizeof(bad)))
				return cli_usage_error("diagnose", "option "
					"'--without': '%s' is not a registered "
					"cause (stray diagnose --causes lists "
					"them)", bad);
			a->without = optarg;
			break;
		case 'X': a->sensor = optarg; break;
		case 'd' + 256: {
			enum stray_detector_kind k;

			if (stray_detector_parse(optarg, &k, NULL) != STRAY_OK)
				return cli_usage_error("diagnose", "option "
					"'--detector': '%s' is not thesis, "
					"window, threshold or tetra3", optarg);
			a->detector = optarg;
			break;
		}
		case 'D' + 256:
			rc = cli_parse_double("diagnose", "detector-sigma",
					      optarg, &a->detector_sigma);
			if (!rc && !(a->detector_sigma >= 0.5 &&
				     a->detector_sigma <= 20.0))
				return cli_usage_error("diagnose", "option "
					"'--detector-sigma': %g is outside "
					"0.5..20", a->detector_sigma);
			break;
		case 'L': a->lens = optarg; break;
		case 'G': a->surfaces = 1; break;
		case 'W': a->model = optarg; break;
		case 'j': cli.json = 1; break;
		case 'n': rc = cli_parse_double("diagnose", "rays", optarg, &a->rays); break;
		case 'k': rc = cli_parse_double("diagnose", "seed", optarg, &a->seed); break;
		case 't': rc = cli_parse_double("diagnose", "threads", optarg, &a->threads); break;
		case 'S':
			if (a->n_sets == DIAG_SETS_MAX)
				return cli_usage_error("diagnose", "too many --set");
			a->sets[a->n_sets++] = optarg;
			break;
		case 'h': fputs(usage, stdout); return -1;
		default: return cli_usage_error("diagnose", "unknown option");
		}
	}
	if (rc || a->list)
		return rc;
	if (optind + 1 != argc)
		return cli_usage_error("diagnose", "expected one MEASURED.csv");
	a->measured = argv[optind];
	if (!a->scene)
		return cli_usage_error("diagnose", "--scene is required");
	if (!(a->rays >= 1000 && a->rays <= 1e10 && a->rays == floor(a->rays)))
		return cli_usage_error("diagnose", "option '--rays': must be an "
				       "integer in [1000, 1e10]");
	if (!(a->seed >= 0 && a->seed <= 9e15 && a->seed == floor(a->seed)))
		return cli_usage_error("diagnose", "option '--seed': must be an "
				       "integer >= 0");
	if (!(a->threads >= 1 && a->threads <= 256 &&
	      a->threads == floor(a->threads)))
		return cli_usage_error("diagnose", "option '--threads': must be "
				       "an integer in [1, 256]");
	return CLI_OK;
}

static void log_line(const char *line)
{
	if (!cli.json)
		fprintf(stderr, "stray diagnose: %s\n", line);
}

static void list_causes(void)
{
	int i, k;

	for (i = 0; diag_causes[i]; i++) {
		printf("%s:", diag_causes[i]->name);
		for (k = 0; k < diag_causes[i]->n_params; k++)
			printf(" %s [%g, %g] %s", diag_causes[i]->param[k].name,
			       diag_causes[i]->param[k].lo,
			       diag_causes[i]->param[k].hi,
			       diag_causes[i]->param[k].unit);
		printf("\n  %s\n", diag_causes[i]->explanation);
	}
}

/* The surface at fault (diagnose/diag_surfaces.h): localise, confirm by
 * a re-trace of the model, write it where the user asked. */
static int surfaces(struct diag_eval *e, const struct diag_data *d,
		    const struct diag_result *r, const char *model,
		    struct diag_surfaces *s, double *base,
		    struct stray_error *err)
{
	struct diag_surf_table *t = NULL;
	const struct diag_fit *f = r->named.n_causes ? &r->named :
		&r->tentative;
	struct diag_state st;
	int rc = STRAY_OK, on = 0, c, o = 0;
	size_t i;

	/* the baffle's surfaces after the lens's causes the registry named
	 * (or its tentative model holds): those are applied first */
	diag_state_nominal(&st);
	for (c = 0; c < f->n_causes; o += f->cause[c]->n_params, c++)
		if (f->cause[c]->needs_lens) {
			f->cause[c]->apply(f->p + o, &st);
			on = 1;
		}
	if (on) {
		double *sig = malloc((d->n ? d->n : 1) * sizeof(*sig));

		rc = sig ? diag_eval_model(e, &st, base, sig, NULL, err) :
			stray_error_set(err, STRAY_ENOMEM, "diagnose",
					"out of memory");
		for (i = 0; !rc && i < d->n; i++)
			base[i] = r->model_before[i] > 0.0 ?
				base[i] / r->model_before[i] : 1.0;
		free(sig);
		if (rc)
			return rc;
	}
	log_line("surface at fault: re-weighting per surface group");
	rc = diag_surf_table_trace(e, &t, err);
	if (!rc)
		rc = diag_surfaces_fit_on(t, d, on ? base : NULL, s, err);
	diag_surf_table_free(t);
	if (!rc)
		rc = diag_surfaces_confirm(e, d, s, err);
	if (!rc && model)
		rc = diag_surfaces_write_model(e, s, model, err);
	return rc;
}

int cmd_diagnose(int argc, char **argv, const struct tracer_runner *runner)
{
	struct diag_surfaces surf;
	double *base = NULL;
	int with_surf = 0;
	struct diag_args a = { .rays = 200000, .seed = 1, .threads = 1 };
	struct stray_error err;
	struct diag_data d;
	struct diag_eval e;
	struct diag_result r;
	int rc, i;

	stray_error_clear(&err);
	rc = parse_args(argc, argv, &a);
	if (rc)
		return rc < 0 ? CLI_OK : rc;
	if (a.list) {
		list_causes();
		return CLI_OK;
	}
	if ((a.spectrum || a.response) &&	/* cause_spectral_slope.c */
	    diag_band_set(a.spectrum, a.response, &err))
		return cli_fail("diagnose", &err);
	if (a.sensor) {	/* refused before any trace, not after */
		struct stray_sensor sn;

		if (stray_sensor_load(a.sensor, &sn, &err))
			return cli_fail("diagnose", &err);
	}
	if (diag_data_load(a.measured, &d, &err))
		return cli_fail("diagnose", &err);
	diag_eval_init(&e, a.scene, d.theta_deg, d.n, runner);
	e.n_paths = (uint64_t)a.rays;
	e.seed = (uint64_t)a.seed;
	e.threads = (int)a.threads;
	e.lens = a.lens;
	e.only = a.only;
	e.without = a.without;
	e.sensor = a.sensor;
	e.detector = a.detector;
	e.detector_sigma = a.detector_sigma;
	e.normalised = d.normalised;
	for (i = 0; i < a.n_sets; i++)
		e.sets[e.n_sets++] = a.sets[i];
	memset(&r, 0, sizeof(r));
	rc = diag_eval_prepare(&e, &err);
	if (!rc)
		rc = diag_run(&e, &d, &r, log_line, &err);
	with_surf = a.surfaces || a.model || (r.significant && !r.explained);
	if (!rc && with_surf) {
		base = malloc((d.n ? d.n : 1) * sizeof(*base));
		rc = base ? surfaces(&e, &d, &r, a.model, &surf, base, &err) :
			stray_error_set(&err, STRAY_ENOMEM, "diagnose",
					"out of memory");
		if (!rc)	/* one verdict: the surface at fault named */
			diag_result_surfaces(&r, &surf);
	}
	if (!rc && a.plot)
		rc = diag_plot(a.plot, &d, &r, &err);
	if (!rc) {
		if (cli.json)
			rc = diag_report_json_surf(&d, &e, &r,
						   with_surf ? &surf : NULL,
						   a.model);
		else {
			diag_report_text(&d, &e, &r);
			if (with_surf)
				diag_report_surfaces_text(&surf, a.model);
		}
	} else {
		rc = cli_fail("diagnose", &err);
	}
	free(base);
	diag_result_free(&r);
	diag_eval_free(&e);
	diag_data_free(&d);
	return rc;
}
