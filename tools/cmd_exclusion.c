/*
 * cmd_exclusion.c - `stray exclusion`: Sun, Moon and Earth-limb exclusion
 * angles of a system attenuation curve (thesis §1, §5.1, fig. 5.1).
 *
 * Each body's alpha_required comes from the FDR model at its photon flux;
 * its exclusion angle is where the curve falls below that for good.  The
 * Moon is also excluded while it is in the field of view, where it
 * saturates the detector (§5.1): its angle is the larger of the two.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "fdr_options.h"
#include "plot.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/exclusion_models.h"
#include "stray/photometry.h"

static const char usage[] =
	"usage: stray exclusion --curve C.csv [--rate R] [--k-sigma K]\n"
	"                       [--earth-albedo A] [--plot F.png] [--json] [options]\n"
	"\n"
	"Exclusion angles of a system attenuation curve (docs/formats.md):\n"
	"the smallest angle beyond which alpha stays below alpha_required.\n"
	"With a sigma column, the angles for alpha -/+ K sigma bracket it.\n"
	"\n"
	"  --curve C.csv       system attenuation curve (required)\n"
	"  --k-sigma K         width of the interval in sigmas (default 1)\n"
	"  (--earth-albedo adds the sunlit Earth limb)\n"
	"  --plot F.png        the curve with alpha_required and the angles\n"
	"  --models            the Sun's angle under every model instead: the\n"
	"                      thesis (eq. 2.18, k_px = 1), consistent k_px, and\n"
	"                      the window, threshold and tetra3 (k = 3, 5)\n"
	"                      detectors, with the failure mode that binds each\n"
	"                      (a Markdown table; with --json a \"models\" list)\n"
	"  --json              machine-readable output\n"
	FDR_SETUP_USAGE;

struct body {
	const char *name;
	double flux, alpha_req;
	struct stray_detector_req req;	/* both failure modes */
	struct stray_exclusion ex;
	int excluded;		/* 0: curve ends above alpha_req */
	double angle_deg;	/* reported angle (Moon: with the field) */
};

struct excl_args {
	const char *curve, *plot;
	double k_sigma;
	int models;		/* --models: stray/exclusion_models.h */
};

static int solve_body(const struct fdr_setup *s, const struct excl_args *a,
		      const struct stray_curve_view *v, struct body *b,
		      struct stray_error *err)
{
	struct stray_fdr_model m;
	int rc;

	fdr_setup_model(s, b->flux, &m);
	/* the detector's answer: below it both false stars and the DRS's
	 * detection meet the requirements (thesis: eq. 2.18 alone) */
	rc = fdr_setup_alpha_required(s, &m, &b->req, err);
	if (rc != STRAY_OK)
		return rc;
	b->alpha_req = b->req.alpha_req;
	/* libstray's one verdict: not excluded (NaN, a reason) is a result */
	rc = stray_exclusion_interval(v, b->alpha_req, a->k_sigma, &b->ex, err);
	b->excluded = rc == STRAY_OK && b->ex.excluded;
	if (!b->excluded)
		b->ex.has_interval = 0;
	b->angle_deg = b->ex.theta_deg;
	return rc;
}

static cJSON *body_json(const struct body *b)
{
	cJSON *o = cJSON_CreateObject();

	cJSON_AddItemToObject(o, "alpha_required", cli_json_number(b->alpha_req));
	cJSON_AddStringToObject(o, "binding",
				stray_failure_mode_name(b->req.binding));
	cJSON_AddItemToObject(o, "alpha_false_stars",
			      cli_json_number(b->req.alpha_false));
	cJSON_AddItemToObject(o, "alpha_lost_stars",
			      cli_json_number(b->req.alpha_lost));
	cJSON_AddItemToObject(o, "flux", cli_json_number(b->flux));
	cJSON_AddBoolToObject(o, "excluded_within_curve", b->excluded);
	if (!b->excluded)
		cJSON_AddStringToObject(o, "reason", b->ex.reason);
	cJSON_AddItemToObject(o, "curve_deg", cli_json_number(b->ex.theta_deg));
	if (b->ex.has_interval) {
		cJSON_AddItemToObject(o, "deg_lo", cli_json_number(b->ex.theta_lo_deg));
		cJSON_AddItemToObject(o, "deg_hi", cli_json_number(
			b->ex.hi_reached ? b->ex.theta_hi_deg : NAN));
	}
	return o;
}

static int print_json(const struct fdr_setup *s, const struct excl_args *a,
		      const struct body *b, int nb)
{
	cJSON *o = cJSON_CreateObject();
	int i;

	cJSON_AddStringToObject(o, "curve", a->curve);
	cJSON_AddStringToObject(o, "sensor", s->sensor.name);
	cJSON_AddItemToObject(o, "rate", cli_json_number(s->rate));
	fdr_setup_json(s, o);
	fdr_setup_detector_json(s, o);
	cJSON_AddItemToObject(o, "fov_half_deg", cli_json_number(s->sensor.fov_half_deg));
	cJSON_AddItemToObject(o, "sun_deg", cli_json_number(b[0].angle_deg));
	cJSON_AddItemToObject(o, "moon_deg", cli_json_number(b[1].angle_deg));
	if (nb > 2)
		cJSON_AddItemToObject(o, "earth_limb_deg",
				      cli_json_number(b[2].angle_deg));
	for (i = 0; i < nb; i++)
		cJSON_AddItemToObject(o, b[i].name, body_json(&b[i]));
	return cli_json_emit(o);
}

static void print_text(const struct fdr_setup *s, const struct excl_args *a,
		       const struct body *b, int nb)
{
	int i;

	printf("Exclusion angles of %s for %s at %g false stars per image\n",
	       a->curve, s->sensor.name, s->rate);
	fdr_setup_print_normalisation(s);
	if (s->detector != STRAY_DET_THESIS)	/* the thesis's text as it was */
		printf("  detector                %s (alpha_required: false "
		       "stars <= %g per image and P(DRS) >= %.2f)\n",
		       stray_detector_name(s->detector), s->rate,
		       s->sensor.pr_drs);
	for (i = 0; i < nb; i++) {
		printf("  %-6s alpha_required %.3e  ", b[i].name, b[i].alpha_req);
		if (s->detector != STRAY_DET_THESIS)
			printf("(%s bind)  ", b[i].req.binding ==
			       STRAY_FAIL_LOST_STARS ? "lost stars" : "false stars");
		if (!b[i].excluded) {
			printf("not excluded by the baffle: %s\n", b[i].ex.reason);
			continue;
		}
		printf("exclusion %6.2f deg", b[i].angle_deg);
		if (i == 1 && b[i].angle_deg != b[i].ex.theta_deg) {
			printf("  (field-of-view edge: the Moon saturates in the field; its FDR alone gives %.2f deg)\n",
			       b[i].ex.theta_deg);
			continue;
		}
		if (b[i].ex.has_interval && b[i].excluded &&
		    isfinite(b[i].ex.theta_lo_deg)) {	/* never "nan deg" */
			if (isfinite(b[i].ex.theta_hi_deg))
				printf("  [%.2f, %s%.2f] at %g sigma",
				       b[i].ex.theta_lo_deg,
				       b[i].ex.hi_reached ? "" : ">",
				       b[i].ex.theta_hi_deg, a->k_sigma);
			else
				printf("  [%.2f, beyond the curve] at %g sigma",
				       b[i].ex.theta_lo_deg, a->k_sigma);
		}
		if (i == 2)
			printf("  (from the limb)");
		putchar('\n');
	}
}

static int plot_exclusion(const struct fdr_setup *s, const struct excl_args *a,
			  const struct stray_curve *c, const struct body *b,
			  int nb, struct stray_error *err);

/* --models: the Sun's angle under every model, side by side (issue 28). */
static int print_models(const struct fdr_setup *s, const struct excl_args *a,
			const struct stray_curve_view *v,
			struct stray_error *err)
{
	struct stray_excl_model m[STRAY_EXCL_MODELS];
	int i, rc = stray_exclusion_models(v, &s->sensor, s->flux.sun,
					   s->flux.drs, s->rate, m, err);

	if (rc != STRAY_OK)
		return rc;
	if (cli.json) {
		cJSON *o = cJSON_CreateObject(), *l = cJSON_CreateArray();

		cJSON_AddStringToObject(o, "curve", a->curve);
		cJSON_AddStringToObject(o, "sensor", s->sensor.name);
		cJSON_AddItemToObject(o, "rate", cli_json_number(s->rate));
		for (i = 0; i < STRAY_EXCL_MODELS; i++) {
			cJSON *r = cJSON_CreateObject();

			cJSON_AddStringToObject(r, "model", m[i].model);
			cJSON_AddStringToObject(r, "detector",
				stray_detector_name(m[i].detector));
			cJSON_AddItemToObject(r, "k_px", cli_json_number(m[i].k_px));
			cJSON_AddItemToObject(r, "alpha_false_stars",
				cli_json_number(m[i].alpha_false));
			cJSON_AddItemToObject(r, "alpha_lost_stars",
				cli_json_number(m[i].alpha_lost));
			cJSON_AddItemToObject(r, "alpha_required",
				cli_json_number(m[i].alpha_req));
			cJSON_AddStringToObject(r, "binding",
				stray_failure_mode_name(m[i].binding));
			cJSON_AddItemToObject(r, "sun_deg",
				cli_json_number(m[i].sun_deg));
			if (!m[i].excluded)
				cJSON_AddStringToObject(r, "reason", m[i].reason);
			cJSON_AddItemToArray(l, r);
		}
		cJSON_AddItemToObject(o, "models", l);
		return cli_json_emit(o) == CLI_OK ? STRAY_OK : CLI_OK + 100;
	}
	printf("Sun exclusion of %s for %s at %g false stars per image\n\n"
	       "| model | alpha_required | Sun exclusion, deg | set by |\n"
	       "| --- | --- | --- | --- |\n", a->curve, s->sensor.name, s->rate);
	for (i = 0; i < STRAY_EXCL_MODELS; i++) {
		printf("| %s | %.3g | ", m[i].model, m[i].alpha_req);
		if (m[i].excluded)
			printf("%.2f", m[i].sun_deg);
		else
			printf("not excluded: %s", m[i].reason);
		printf(" | %s |\n", m[i].binding == STRAY_FAIL_LOST_STARS ?
		       "lost stars (P(DRS) < Pr_drs)" : "false stars");
	}
	return STRAY_OK;
}

static int parse_args(int argc, char **argv, struct fdr_setup *s,
		      struct excl_args *a)
{
	static const struct option opts[] = {
		FDR_SETUP_LONG_OPTIONS,
		{ "curve", required_argument, NULL, 'c' },
		{ "k-sigma", required_argument, NULL, 'K' },
		{ "plot", required_argument, NULL, 'p' },
		{ "models", no_argument, NULL, 'M' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc = CLI_OK;

	while (rc == CLI_OK && (opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 0: break;
		case 'h': fputs(usage, stdout); return -1;
		case 'c': a->curve = optarg; break;
		case 'p': a->plot = optarg; break;
		case 'M': a->models = 1; break;
		case 'K': rc = cli_parse_double("exclusion", "k-sigma", optarg, &a->k_sigma); break;
		case '?':
			return cli_usage_error("exclusion", "unknown option '%s'",
					       argv[optind - 1]);
		default:
			rc = fdr_setup_option(s, "exclusion", opt, optarg);
			rc = rc == 1 ? CLI_OK : rc ? rc : CLI_USAGE;
		}
	}
	if (rc != CLI_OK)
		return rc;
	if (optind < argc)
		return cli_usage_error("exclusion", "unexpected argument '%s'",
				       argv[optind]);
	if (!a->curve)
		return cli_usage_error("exclusion", "--curve is required");
	if (!(a->k_sigma >= 0.0))
		return cli_usage_error("exclusion", "option '--k-sigma': must be >= 0");
	if (a->models && (s->detector_name || a->plot || s->map_path ||
			  s->poisson || s->detector_noise))
		return cli_usage_error("exclusion", "--models gives every "
			"normalisation and detector itself: not with --detector, "
			"--map, --noise, --detector-noise or --plot");
	return CLI_OK;
}

int cmd_exclusion(int argc, char **argv)
{
	struct fdr_setup s;
	struct excl_args a = { NULL, NULL, 1.0, 0 };
	struct body b[3] = { { .name = "sun" }, { .name = "moon" },
			     { .name = "earth" } };
	struct stray_curve c;
	struct stray_curve_view v;
	struct stray_error err;
	int rc, i, nb;

	fdr_setup_init(&s);
	stray_error_clear(&err);
	rc = parse_args(argc, argv, &s, &a);
	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	if (fdr_setup_load(&s, &err) != STRAY_OK)
		return cli_fail("exclusion", &err);
	b[0].flux = s.flux.sun;
	b[1].flux = fdr_setup_moon_flux(&s);
	nb = s.earth_given ? 3 : 2;
	if (s.earth_given && fdr_setup_earth_flux(&s, &b[2].flux, &err))
		return cli_fail("exclusion", &err);
	if (stray_curve_load(a.curve, &c, &err) != STRAY_OK)
		return cli_fail("exclusion", &err);
	v = stray_curve_view_of(&c);
	if (a.models) {
		rc = print_models(&s, &a, &v, &err);
		stray_curve_free(&c);
		return rc == STRAY_OK ? CLI_OK : rc == CLI_OK + 100 ?
			CLI_OK : cli_fail("exclusion", &err);
	}
	for (i = 0, rc = STRAY_OK; i < nb && rc == STRAY_OK; i++)
		rc = solve_body(&s, &a, &v, &b[i], &err);
	if (rc == STRAY_OK) {	/* §5.1: the Moon saturates in the field */
		if (b[1].excluded &&	/* never turn "not excluded" into an angle */
		    !(b[1].angle_deg > s.sensor.fov_half_deg))
			b[1].angle_deg = s.sensor.fov_half_deg;
		if (a.plot)
			rc = plot_exclusion(&s, &a, &c, b, nb, &err);
	}
	stray_curve_free(&c);
	if (rc != STRAY_OK)
		return cli_fail("exclusion", &err);
	rc = CLI_OK;
	if (cli.json)
		rc = print_json(&s, &a, b, nb);
	else
		print_text(&s, &a, b, nb);
	fflush(stdout);
	for (i = 0; i < nb; i++)	/* a result, not an error: exit 0 */
		if (!b[i].excluded)
			cli_note("exclusion", "%s: %s not excluded within the "
				 "curve (alpha_required %.3g): %s", a.curve,
				 b[i].name, b[i].alpha_req, b[i].ex.reason);
	return rc;
}

static int plot_exclusion(const struct fdr_setup *s, const struct excl_args *a,
			  const struct stray_curve *c, const struct body *b,
			  int nb, struct stray_error *err)
{
	static const enum plot_color color[3] = { PLOT_RED, PLOT_GREY, PLOT_GREEN };
	struct plot_series series[1 + 2 * 3];
	double hx[3][2], hy[3][2], vx[3][2], vy[3][2];
	double lo[c->n ? c->n : 1], hi[c->n ? c->n : 1], amin = INFINITY;
	char label[3][2][64], title[200];
	size_t i, ns = 0;
	int k;

	for (i = 0; i < c->n; i++) {
		lo[i] = c->sigma ? c->alpha[i] - c->sigma[i] : c->alpha[i];
		hi[i] = c->sigma ? c->alpha[i] + c->sigma[i] : c->alpha[i];
		if (c->alpha[i] > 0.0)
			amin = fmin(amin, c->alpha[i]);
	}
	series[ns++] = (struct plot_series){ c->theta_deg, c->alpha, c->n,
		c->sigma ? lo : NULL, c->sigma ? hi : NULL, PLOT_BLUE,
		PLOT_LINE, "system attenuation #ga#dsys#u" };
	for (k = 0; k < nb; k++) {
		amin = fmin(amin, b[k].alpha_req);
		hx[k][0] = c->theta_deg[0];
		hx[k][1] = c->theta_deg[c->n - 1];
		hy[k][0] = hy[k][1] = b[k].alpha_req;
		snprintf(label[k][0], 64, "#ga#dreq#u %s", b[k].name);
		series[ns++] = (struct plot_series){ hx[k], hy[k], 2, NULL,
			NULL, color[k], PLOT_DASHED, label[k][0] };
		if (isnan(b[k].angle_deg))
			continue;
		vx[k][0] = vx[k][1] = b[k].angle_deg;
		vy[k][0] = 1e-300;
		vy[k][1] = 10.0;
		snprintf(label[k][1], 64, "%s exclusion %.1f#uo#d", b[k].name,
			 b[k].angle_deg);
		series[ns++] = (struct plot_series){ vx[k], vy[k], 2, NULL,
			NULL, color[k], PLOT_DOTTED, label[k][1] };
	}
	snprintf(title, sizeof(title), "%s: exclusion angles at %g false stars/image",
		 s->sensor.name, s->rate);
	{
		struct plot_spec p = { a->plot, title,
			"off-axis angle #gh [deg]", "attenuation #ga", 0, 1,
			NAN, NAN, amin / 10.0, 3.0, series, ns, 0 };

		return plot_render(&p, err);
	}
}
