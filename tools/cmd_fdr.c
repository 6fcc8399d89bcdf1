/*
 * cmd_fdr.c - `stray fdr`: the false-detection rate of a sensor as a
 * function of system attenuation, and the attenuation that a tolerated
 * rate requires (thesis §2.3, eq. 2.3-2.18, fig. 2.7).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "fdr_options.h"
#include "plot.h"
#include "stray/sky_coverage.h"
#include "stray/photometry.h"

static const char usage[] =
	"usage: stray fdr [--source sun|moon|earth] [--rate R] [--alpha A]\n"
	"                 [--plot F.png] [--json] [options]\n"
	"\n"
	"The attenuation alpha_required at which the sensor sees R false stars\n"
	"per image (default: the sensor's fdr_tolerated), and with --alpha the\n"
	"false-detection rate at that attenuation.  With --detector, the\n"
	"detector's own models: its false stars per image and the reference\n"
	"star's detection probability, alpha_required the smaller of the two\n"
	"attenuations that meet --rate and the sensor's pr_drs (docs/detectors.md).\n"
	"\n"
	"  --source B          stray-light source: sun (default), moon, earth\n"
	"  --alpha A           also give FDR at system attenuation A\n"
	"  --plot F.png        FDR vs alpha with the tolerated rate (fig. 2.7)\n"
	"  --json              machine-readable output\n"
	FDR_SETUP_USAGE;

struct fdr_args {
	const char *source;
	double alpha;
	int has_alpha;
	const char *plot;
};

struct fdr_result {
	double f_src, i_drs, i_sdt, alpha_req, log10_fdr;
	struct stray_detector det;
	struct stray_detector_req req;
	double p_drs, limiting_mag;	/* at --alpha */
	double sky_coverage;		/* fraction with min_stars found */
	int min_stars;
};

/* Photon flux of the chosen source. */
static int source_flux(const struct fdr_setup *s, const struct fdr_args *a,
		       double *f, struct stray_error *err)
{
	if (strcmp(a->source, "sun") == 0) {
		*f = s->flux.sun;
		return STRAY_OK;
	}
	if (strcmp(a->source, "moon") == 0) {
		*f = fdr_setup_moon_flux(s);
		return STRAY_OK;
	}
	return fdr_setup_earth_flux(s, f, err);
}

static int plot_fdr(const struct fdr_setup *s, const struct fdr_args *a,
		    const struct stray_fdr_model *m, const struct fdr_result *r,
		    struct stray_error *err)
{
	enum { N = 241 };
	double al[N], fdr[N], hx[2], hy[2], vx[2], vy[2], ymax;
	char title[160];
	int i, rc;

	for (i = 0; i < N; i++) {	/* a decade below to 2.5 above */
		double lf;

		al[i] = r->alpha_req * pow(10.0, -1.0 + 3.5 * i / (N - 1));
		rc = stray_fdr_log_rate(m, al[i], r->i_sdt, &lf, err);
		if (rc != STRAY_OK)
			return rc;
		fdr[i] = exp(lf);
	}
	ymax = m->n_tot / m->n_pps;
	hx[0] = al[0]; hx[1] = al[N - 1]; hy[0] = hy[1] = s->rate;
	vx[0] = vx[1] = r->alpha_req; vy[0] = 1e-6; vy[1] = ymax;
	{
		const struct plot_series series[] = {
			{ al, fdr, N, NULL, NULL, PLOT_BLUE, PLOT_LINE,
			  "false detection rate" },
			{ hx, hy, 2, NULL, NULL, PLOT_RED, PLOT_DASHED,
			  "tolerated rate" },
			{ vx, vy, 2, NULL, NULL, PLOT_GREY, PLOT_DOTTED,
			  "alpha required" },
		};
		struct plot_spec p = {
			a->plot, title, "system attenuation #ga#dsys#u",
			"false detections per image", 1, 1, al[0], al[N - 1],
			1e-6, ymax * 3.0, series, 3, 0
		};

		snprintf(title, sizeof(title),
			 "%s, %s: #ga#dreq#u = %.3g at %g per image",
			 s->sensor.name, a->source, r->alpha_req, s->rate);
		return plot_render(&p, err);
	}
}

/* Both failure modes at --alpha: false stars per image, the DRS's
 * detection probability and the limiting magnitude (eq. 2.2 from the DRS:
 * the faintest star found with Pr_drs). */
static int alpha_figures(const struct fdr_setup *s, const struct fdr_args *a,
			 const struct stray_fdr_model *m, struct fdr_result *r,
			 struct stray_error *err)
{
	double lf, lim_e;
	int rc;

	if (!(a->alpha >= 0.0 && isfinite(a->alpha)))
		return stray_error_set_value(err, STRAY_EINVAL, "alpha",
			"must be finite and >= 0", a->alpha);
	if ((rc = stray_detector_log_false_rate(&r->det, m, a->alpha, &lf,
						err)) != STRAY_OK ||
	    (rc = stray_detector_star_prob(&r->det, m, a->alpha, r->i_drs,
					   &r->p_drs, err)) != STRAY_OK ||
	    (rc = stray_detector_limiting_e(&r->det, m, a->alpha,
					    s->sensor.pr_drs, &lim_e, err)) !=
		    STRAY_OK)
		return rc;
	r->log10_fdr = lf / log(10.0);
	r->limiting_mag = s->sensor.drs_mag - 2.5 * log10(lim_e / r->i_drs);
	r->min_stars = s->sensor.min_stars > 0.0 ? (int)s->sensor.min_stars : 4;
	return sky_coverage(&s->sensor, r->limiting_mag, r->min_stars,
			    &r->sky_coverage, err);
}

static int print_result(const struct fdr_setup *s, const struct fdr_args *a,
			const struct fdr_result *r)
{
	if (cli.json) {
		cJSON *o = cJSON_CreateObject();

		cJSON_AddStringToObject(o, "sensor", s->sensor.name);
		cJSON_AddStringToObject(o, "source", a->source);
		cJSON_AddStringToObject(o, "noise", s->poisson ? "poisson" : "gauss");
		/* the real detectors' models always carry it (fdr_setup.c) */
		cJSON_AddBoolToObject(o, "detector_noise", s->detector_noise ||
				      s->detector != STRAY_DET_THESIS);
		fdr_setup_json(s, o);
		cJSON_AddItemToObject(o, "source_flux", cli_json_number(r->f_src));
		cJSON_AddItemToObject(o, "rate", cli_json_number(s->rate));
		cJSON_AddItemToObject(o, "drs_e", cli_json_number(r->i_drs));
		cJSON_AddItemToObject(o, "threshold_e", cli_json_number(r->i_sdt));
		cJSON_AddItemToObject(o, "alpha_required",
				      cli_json_number(r->alpha_req));
		fdr_setup_detector_json(s, o);
		if (s->detector == STRAY_DET_THRESHOLD)
			cJSON_AddItemToObject(o, "pixel_threshold_e",
				cli_json_number(r->det.pixel_t_e));
		cJSON_AddItemToObject(o, "pr_drs",
				      cli_json_number(s->sensor.pr_drs));
		cJSON_AddItemToObject(o, "alpha_false_stars",
			cli_json_number(r->req.alpha_false));
		cJSON_AddItemToObject(o, "alpha_lost_stars",
			cli_json_number(r->req.alpha_lost));
		cJSON_AddStringToObject(o, "binding",
			stray_failure_mode_name(r->req.binding));
		if (a->has_alpha) {
			cJSON_AddItemToObject(o, "alpha", cli_json_number(a->alpha));
			cJSON_AddItemToObject(o, "fdr",
				cli_json_number(pow(10.0, r->log10_fdr)));
			cJSON_AddItemToObject(o, "log10_fdr",
				cli_json_number(r->log10_fdr));
			cJSON_AddItemToObject(o, "false_stars_per_image",
				cli_json_number(pow(10.0, r->log10_fdr)));
			cJSON_AddItemToObject(o, "drs_detection_probability",
				cli_json_number(r->p_drs));
			cJSON_AddItemToObject(o, "limiting_mag",
				cli_json_number(r->limiting_mag));
			cJSON_AddItemToObject(o, "sky_coverage",
				cli_json_number(r->sky_coverage));
			cJSON_AddItemToObject(o, "min_stars",
				cli_json_number(r->min_stars));
			cJSON_AddStringToObject(o, "sky_coverage_stars",
						SKY_COVERAGE_SOURCE);
		}
		return cli_json_emit(o);
	}
	printf("False-detection model (thesis §2.3) for %s, source %s\n",
	       s->sensor.name, a->source);
	printf("  source photon flux      %.4e ph/s/m^2\n", r->f_src);
	printf("  DRS photons I_drs       %.2f e-   (m = %.2f, eq. 2.12)\n",
	       r->i_drs, s->sensor.drs_mag);
	printf("  threshold I_sdt         %.2f e-   (Pr_drs = %.2f, eq. 2.16)\n",
	       r->i_sdt, s->sensor.pr_drs);
	printf("  noise model             %s%s\n",
	       s->poisson ? "exact Poisson" : "Gaussian (thesis)",
	       s->detector_noise || s->detector != STRAY_DET_THESIS ?
	       " + read noise and dark current" : "");
	fdr_setup_print_normalisation(s);
	printf("  detector                %s%s\n",
	       stray_detector_name(s->detector),
	       s->detector == STRAY_DET_THESIS ?
	       " (eq. 2.18 as published)" : "");
	if (s->detector != STRAY_DET_THESIS)
		printf("  alpha where false stars reach %g: %.4e, where P(DRS) "
		       "falls to %.2f: %.4e\n", s->rate, r->req.alpha_false,
		       s->sensor.pr_drs, r->req.alpha_lost);
	printf("  alpha_required          %.4e   (%s bind; FDR = %g per "
	       "image)\n", r->alpha_req,
	       r->req.binding == STRAY_FAIL_LOST_STARS ? "lost stars" :
	       "false stars", s->rate);
	if (a->has_alpha) {
		printf("  FDR at alpha %-10.4g %.4e per image (log10 %.3f)\n",
		       a->alpha, pow(10.0, r->log10_fdr), r->log10_fdr);
		printf("  P(DRS detected)         %.4f   (m = %.2f)\n",
		       r->p_drs, s->sensor.drs_mag);
		printf("  limiting magnitude      %.3f   (detected with "
		       "Pr_drs = %.2f)\n", r->limiting_mag, s->sensor.pr_drs);
		printf("  sky coverage            %.3f   (>= %d stars that "
		       "bright in the field; %s)\n", r->sky_coverage,
		       r->min_stars, SKY_COVERAGE_SOURCE);
	}
	return CLI_OK;
}

static int parse_args(int argc, char **argv, struct fdr_setup *s,
		      struct fdr_args *a)
{
	static const struct option opts[] = {
		FDR_SETUP_LONG_OPTIONS,
		{ "source", required_argument, NULL, 's' },
		{ "alpha", required_argument, NULL, 'a' },
		{ "plot", required_argument, NULL, 'p' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc;

	while ((rc = cli_next_option("fdr", argc, argv, opts, usage,
				     &opt)) == CLI_OK && opt != -1) {
		switch (opt) {
		case 's': a->source = optarg; break;
		case 'p': a->plot = optarg; break;
		case 'a':
			if (cli_parse_double("fdr", "alpha", optarg, &a->alpha))
				return CLI_USAGE;
			a->has_alpha = 1;
			break;
		default:
			rc = fdr_setup_option(s, "fdr", opt, optarg);
			if (rc != 1)
				return rc ? rc : CLI_USAGE;
		}
	}
	if (rc == CLI_OK)
		rc = cli_no_operands("fdr", argc, argv);
	if (rc != CLI_OK)
		return rc;
	if (strcmp(a->source, "sun") && strcmp(a->source, "moon") &&
	    strcmp(a->source, "earth"))
		return cli_usage_error("fdr", "option '--source': '%s' is not sun, moon or earth",
				       a->source);
	return CLI_OK;
}

int cmd_fdr(int argc, char **argv)
{
	struct fdr_setup s;
	struct fdr_args a = { "sun", NAN, 0, NULL };
	struct fdr_result r;
	struct stray_fdr_model m;
	struct stray_error err;
	int rc;

	fdr_setup_init(&s);
	stray_error_clear(&err);
	rc = parse_args(argc, argv, &s, &a);
	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	if (fdr_setup_load(&s, &err) != STRAY_OK ||
	    source_flux(&s, &a, &r.f_src, &err) != STRAY_OK)
		return cli_fail("fdr", &err);
	fdr_setup_model(&s, r.f_src, &m);
	r.i_drs = stray_fdr_drs_photons(&m);
	r.log10_fdr = NAN;
	if (stray_fdr_threshold(&m, &r.i_sdt, &err) != STRAY_OK ||
	    fdr_setup_detector(&s, &m, &r.det, &err) != STRAY_OK ||
	    fdr_setup_alpha_required(&s, &m, &r.req, &err) != STRAY_OK)
		return cli_fail("fdr", &err);
	r.alpha_req = r.req.alpha_req;
	if (a.has_alpha && alpha_figures(&s, &a, &m, &r, &err) != STRAY_OK)
		return cli_fail("fdr", &err);
	if (a.plot && plot_fdr(&s, &a, &m, &r, &err) != STRAY_OK)
		return cli_fail("fdr", &err);
	return print_result(&s, &a, &r);
}
