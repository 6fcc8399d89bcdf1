/*
 * cmd_frames.c - `stray frames`: its options, one call of the library
 * (frames_run, frames/frames_job.h: detector frames rendered, two star
 * detectors, false stars counted against the FDR model and its
 * extension) and its output (frames_report.c); issue 13 items 3-5.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_capture.h"
#include "commands.h"
#include "fdr_options.h"
#include "frames_report.h"
#include "frames_plot.h"
#include "frames/frames_job.h"

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

/* The command line: the run's options and what only the command uses. */
struct frames_args {
	struct frames_opts o;
	const char *plot_csv, *plot;	/* --plot-validation, --plot */
	int detector;		/* --detector: 1 thesis, 0 threshold */
};

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

	if (sscanf(v, "%lf,%lf,%lf,%lf%c", &a->o.att[0], &a->o.att[1], &a->o.att[2],
		   &a->o.att[3], &tail) != 4)
		return cli_usage_error("frames", "option '--attitude': '%s' is not q_c,e1,e2,e3", v);
	n = sqrt(a->o.att[0] * a->o.att[0] + a->o.att[1] * a->o.att[1] +
		 a->o.att[2] * a->o.att[2] + a->o.att[3] * a->o.att[3]);
	if (!(n > 1e-9) || !isfinite(n))
		return cli_usage_error("frames", "option '--attitude': '%s' is not a rotation", v);
	a->o.att[0] /= n;
	a->o.att[1] /= n;
	a->o.att[2] /= n;
	a->o.att[3] /= n;
	a->o.has_att = 1;
	return CLI_OK;
}

static int parse_opt(struct fdr_setup *s, struct frames_args *a, int opt)
{
	switch (opt) {
	case 'c': a->o.curve = optarg; return CLI_OK;
	case 'm': a->o.map = optarg; return CLI_OK;
	case 'o': a->o.out_dir = optarg; return CLI_OK;
	case 'P': a->o.png = optarg; return CLI_OK;
	case 'V': a->plot_csv = optarg; return CLI_OK;
	case 'p': a->plot = optarg; return CLI_OK;
	case 't': a->o.has_theta = 1;
		return cli_parse_double("frames", "theta", optarg, &a->o.theta_deg);
	case 'a': a->o.has_alpha = 1;
		return cli_parse_double("frames", "alpha", optarg, &a->o.alpha);
	case 'n': return cli_parse_count("frames", "frames", optarg, 1, 1e6,
					 &a->o.frames);
	case 'w': return cli_parse_count("frames", "window", optarg, 32, 4096,
					 &a->o.window);
	case 'k': return cli_parse_count("frames", "seed", optarg, 0, 4e9,
					 &a->o.seed);
	case 'v': return cli_parse_count("frames", "save", optarg, 0, 1000,
					 &a->o.save);
	case 'g': return cli_parse_double("frames", "mag-max", optarg,
					  &a->o.mag_max);
	case 'd': return parse_choice("detector", optarg, "thesis", "threshold",
				      &a->detector);
	case 'q': return parse_attitude(optarg, a);
	case 'C': a->o.catalogue = optarg; return CLI_OK;
	case 'T': a->o.truth = optarg; return CLI_OK;
	case 'E': return cli_parse_double("frames", "epoch", optarg, &a->o.epoch);
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
	if (a->o.has_alpha == (a->o.curve != NULL))
		return cli_usage_error("frames", "give --curve with --theta, or --alpha");
	if ((a->o.catalogue || a->o.truth) && !a->o.has_att)
		return cli_usage_error("frames", "--catalogue and --truth-stars need --attitude");
	if (!(a->o.epoch > 1000.0 && a->o.epoch < 3000.0))
		return cli_usage_error("frames", "option '--epoch': %g is not a Julian year in 1000..3000",
				       a->o.epoch);
	if (a->o.curve && !a->o.has_theta)
		return cli_usage_error("frames", "--curve needs --theta");
	if (a->o.has_theta && !(a->o.theta_deg >= 0.0 && a->o.theta_deg <= 180.0))
		return cli_usage_error("frames", "option '--theta': %g is outside 0..180 deg",
				       a->o.theta_deg);
	if (a->o.has_alpha && !(a->o.alpha >= 0.0))
		return cli_usage_error("frames", "option '--alpha': %g must be >= 0",
				       a->o.alpha);
	if (!(a->o.mag_max > -2.0 && a->o.mag_max <= 14.0))
		return cli_usage_error("frames", "option '--mag-max': %g is outside -2..14",
				       a->o.mag_max);
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

static int capture_frame(void *user, const uint16_t *dn, int cols, int rows,
			 size_t index, size_t total, struct stray_error *err)
{
	(void)user;
	return cli_capture_frame(dn, cols, rows, index, total, err);
}

int cmd_frames(int argc, char **argv)
{
	struct frames_job *st = calloc(1, sizeof(*st));
	struct fdr_setup s;
	struct frames_args a;
	struct stray_error err;
	int rc;

	if (!st)
		return CLI_FAIL;
	fdr_setup_init(&s);
	stray_error_clear(&err);
	memset(&a, 0, sizeof(a));
	frames_opts_init(&a.o);
	if (cli_capturing())	/* a library call keeps every frame */
		a.o.on_frame = capture_frame;
	a.detector = 1;
	rc = parse_args(argc, argv, &s, &a);
	if (rc == CLI_OK && a.plot_csv) {
		if (frames_plot_validation(a.plot_csv, a.plot, &err))
			rc = cli_fail("frames", &err);
	} else if (rc == CLI_OK) {
		if (fdr_setup_load(&s, &err) || frames_run(st, &s, &a.o, &err))
			rc = cli_fail("frames", &err);
		else if (cli.json)
			rc = frames_print_json(st, a.detector);
		else
			frames_print_text(st);
	}
	frames_job_free(st);
	free(st);
	return rc < 0 ? CLI_OK : rc;
}
