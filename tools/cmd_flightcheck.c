/*
 * cmd_flightcheck.c - `stray flightcheck FRAMES --aem A --model M`: the
 * stray-light curve measured from flight frames, made absolute by the
 * catalogue stars in the same frames, against the predicted curve (issue
 * 18, thesis §4.3).  The analysis is libmission (fc_check_run,
 * mission/flightcheck_check.c); this file parses, prints and plots.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "commands.h"
#include "fdr_options.h"
#include "mission/flightcheck_check.h"
#include "plot.h"
#include "stray/errfmt.h"
#include "stray/curve_io.h"

static const char usage[] =
	"usage: stray flightcheck FRAMES_DIR|FRAME.fits... --aem A.aem --model M.csv\n"
	"                         [--catalogue CAT] [--oem O.oem] [--moon-min DEG]\n"
	"                         [--limb-min DEG] [--sensor S] [--normalisation N]\n"
	"                         [--out C.csv]\n"
	"                         [--plot P.png] [--json]\n"
	"\n"
	"Flight frames (a folder, with or without manifest.csv, or a list of FITS\n"
	"files: each with EXPTIME, BIAS and GAIN, the\n"
	"mid-exposure from DATE-AVG, DATE-BEG/DATE-END or DATE-OBS in TIMESYS)\n"
	"and the head's attitude (CCSDS AEM, boresight +z of the body): per\n"
	"frame the Sun offset angle, a robust background (tile medians, plane:\n"
	"gradient), the catalogue stars (--catalogue, else the synthetic sky)\n"
	"at the frame's epoch (proper motion), their V and B-V taken to the\n"
	"passband (a blackbody colour term, docs/flightcheck.md), placed\n"
	"by the attitude and refined on the matches; the stars' magnitudes and\n"
	"the passband photometry calibrate DN per photo-electron (eq. 2.2,\n"
	"2.12), hence alpha_px(theta) absolutely (eq. 2.3).  Against the model\n"
	"curve: the best scale alpha_px / alpha_model with its interval, the\n"
	"shape test (chi2 of the scaled model) and the scale over the model's\n"
	"k_px (1 when the model's normalisation is right).  Refused (exit 1)\n"
	"when the frames cannot be calibrated: fewer than 3 calibrators, under\n"
	"30 % of the bright predicted stars found, or a plate residual over\n"
	"1.5 px.\n"
	"\n"
	"  --aem A.aem         attitude of the head (CCSDS 504.0 quaternions)\n"
	"  --model M.csv       predicted system curve alpha(theta) (stray trace)\n"
	"  --catalogue CAT     Hipparcos hip2.dat or hip_main.dat, Yale BSC5, or a\n"
	"                      CSV (ra_deg,dec_deg,v_mag,b_v[,hip,pmra_mas_yr,\n"
	"                      pmdec_mas_yr,epoch_jyear,hp_mag])\n"
	"  --oem O.oem         the orbit (CCSDS 502.0): the Moon seen from the\n"
	"                      spacecraft and the Earth limb's angle per frame\n"
	"  --moon-min DEG      frames with the Moon nearer the boresight are left\n"
	"                      out of the scale fit (25)\n"
	"  --limb-min DEG      the same for the Earth limb (30; needs --oem)\n"
	SENSOR_USAGE
	NORMALISATION_USAGE
	"  --out C.csv         the flight curve: theta_deg, alpha (= alpha_px /\n"
	"                      k_px, absolute), sigma, model; for stray diagnose\n"
	"  --plot P.png        measured alpha_px vs the scaled model\n"
	"  --json              machine-readable output\n";

struct fc_args {
	const char *dir, *aem, *model, *out, *plot, *catalogue, *oem;
	double moon_min, limb_min;
	char cat_name[64];	/* "synthetic" or "<kind> <file>" */
};

static int cmp_theta(const void *a, const void *b)
{
	const struct fc_point *p = a, *q = b;

	return (p->theta_deg > q->theta_deg) - (p->theta_deg < q->theta_deg);
}

static int plot(const char *path, const struct fc_point *p, size_t n,
		const struct fc_summary *s, struct stray_error *err)
{
	double *x = malloc(n * sizeof(double) * 5), *y, *lo, *hi, *m;
	struct plot_series sr[2];
	struct plot_spec sp;
	size_t i;
	int rc;

	if (!x)
		return stray_error_set(err, STRAY_ENOMEM, "plot", "out of memory");
	y = x + n;
	lo = y + n;
	hi = lo + n;
	m = hi + n;
	for (i = 0; i < n; i++) {
		x[i] = p[i].theta_deg;
		y[i] = p[i].alpha_px;
		lo[i] = fmax(y[i] - p[i].sigma, 1e-30);
		hi[i] = y[i] + p[i].sigma;
		m[i] = s->scale * p[i].model;
	}
	memset(sr, 0, sizeof(sr));
	sr[0] = (struct plot_series){ x, y, n, lo, hi, PLOT_BLUE, PLOT_POINTS,
				      "measured alpha_px (star-calibrated)" };
	sr[1] = (struct plot_series){ x, m, n, NULL, NULL, PLOT_RED, PLOT_LINE,
				      "model x best scale" };
	memset(&sp, 0, sizeof(sp));
	sp.path = path;
	sp.title = "Flight check: stray light from the tracker's own frames";
	sp.xlabel = "Sun offset angle [deg]";
	sp.ylabel = "alpha_px";
	sp.log_y = 1;
	sp.x_min = sp.x_max = NAN;
	sp.y_min = INFINITY;
	sp.y_max = 0.0;
	for (i = 0; i < n; i++) {	/* both series in view */
		sp.y_min = fmin(sp.y_min, fmin(lo[i], m[i] > 0.0 ? m[i] : INFINITY));
		sp.y_max = fmax(sp.y_max, fmax(hi[i], m[i]));
	}
	sp.y_min = isfinite(sp.y_min) && sp.y_min > 0.0 ? sp.y_min / 1.5 : NAN;
	sp.y_max = sp.y_max > 0.0 ? sp.y_max * 1.5 : NAN;
	sp.legend_bottom = 1;
	sp.series = sr;
	sp.n_series = 2;
	rc = plot_render(&sp, err);
	free(x);
	return rc;
}

static int emit_json(const struct fc_args *a, const struct fc_frame *f,
		     const struct fc_point *p, size_t n,
		     const struct fc_summary *s)
{
	cJSON *o = cJSON_CreateObject(), *fr = cJSON_CreateArray();
	size_t i;

	/* the verdict first (the report shows the first rows) */
	cJSON_AddItemToObject(o, "scale_over_k_px", cli_json_number(s->scale_over_kpx));
	cJSON_AddItemToObject(o, "scale_over_k_px_sigma",
			      cli_json_number(s->scale_over_kpx_sigma));
	{	/* the 95 % interval */
		cJSON *iv = cJSON_CreateArray();

		cJSON_AddItemToArray(iv, cli_json_number(s->scale_over_kpx -
					1.96 * s->scale_over_kpx_sigma));
		cJSON_AddItemToArray(iv, cli_json_number(s->scale_over_kpx +
					1.96 * s->scale_over_kpx_sigma));
		cJSON_AddItemToObject(o, "scale_over_k_px_interval", iv);
	}
	cJSON_AddItemToObject(o, "shape_chi2_dof", cli_json_number(s->chi2_dof));
	cJSON_AddItemToObject(o, "scale", cli_json_number(s->scale));
	cJSON_AddItemToObject(o, "scale_sigma", cli_json_number(s->scale_sigma));
	cJSON_AddItemToObject(o, "scale_sigma_stat", cli_json_number(s->scale_sigma_stat));
	cJSON_AddItemToObject(o, "k_px_model", cli_json_number(s->k_px_model));
	cJSON_AddItemToObject(o, "dn_per_e", cli_json_number(s->dn_per_e));
	cJSON_AddItemToObject(o, "dn_per_e_sigma", cli_json_number(s->dn_per_e_sigma));
	cJSON_AddNumberToObject(o, "calibration_stars", s->n_cal);
	cJSON_AddItemToObject(o, "calibration_chi2_dof", cli_json_number(s->cal_chi2_dof));
	cJSON_AddNumberToObject(o, "frames", (double)n);
	cJSON_AddStringToObject(o, "catalogue", a->cat_name);
	cJSON_AddNumberToObject(o, "stars_predicted", s->n_pred);
	cJSON_AddNumberToObject(o, "stars_matched", s->n_match);
	cJSON_AddItemToObject(o, "match_fraction", cli_json_number(s->match_frac));
	cJSON_AddItemToObject(o, "plate_residual_px", cli_json_number(s->resid_px));
	cJSON_AddNumberToObject(o, "frames_screened", s->n_screened);
	cJSON_AddStringToObject(o, "frames_dir", a->dir);
	for (i = 0; i < n; i++) {
		cJSON *e = cJSON_CreateObject();

		cJSON_AddItemToObject(e, "theta_deg", cli_json_number(f[i].theta_deg));
		cJSON_AddItemToObject(e, "alpha_px", cli_json_number(p[i].alpha_px));
		cJSON_AddItemToObject(e, "sigma", cli_json_number(p[i].sigma));
		cJSON_AddItemToObject(e, "model", cli_json_number(p[i].model));
		cJSON_AddItemToObject(e, "background_dn", cli_json_number(f[i].bg_dn));
		cJSON_AddItemToObject(e, "gradient_dn_per_px",
				      cli_json_number(f[i].grad_dn_per_px));
		cJSON_AddItemToObject(e, "gradient_dir_deg",
				      cli_json_number(f[i].grad_dir_deg));
		cJSON_AddNumberToObject(e, "stars_predicted", f[i].n_pred);
		cJSON_AddNumberToObject(e, "stars_matched", f[i].n_match);
		cJSON_AddNumberToObject(e, "calibrators", f[i].n_cal);
		cJSON_AddItemToObject(e, "shift_px",
				      cli_json_number(hypot(f[i].dx_px, f[i].dy_px)));
		cJSON_AddItemToObject(e, "rotation_deg", cli_json_number(f[i].rot_deg));
		cJSON_AddItemToObject(e, "residual_px", cli_json_number(f[i].resid_px));
		cJSON_AddItemToObject(e, "moon_deg", cli_json_number(f[i].moon_deg));
		cJSON_AddItemToObject(e, "earth_limb_deg", cli_json_number(f[i].limb_deg));
		cJSON_AddBoolToObject(e, "screened", f[i].screened);
		cJSON_AddItemToArray(fr, e);
	}
	cJSON_AddItemToObject(o, "per_frame", fr);
	return cli_json_emit(o);
}

static void print_text(const struct fc_args *a, const struct fc_frame *f,
		       const struct fc_point *p, size_t n,
		       const struct fc_summary *s)
{
	size_t i;

	printf("Flight check: %zu frames, catalogue %s\n", n, a->cat_name);
	printf("  plate: %d of %d predicted stars found; of the bright ones %d of %d (%.2f); residual %.2f px\n",
	       s->n_match, s->n_pred, s->n_sure_found, s->n_sure,
	       s->match_frac, s->resid_px);
	if (s->n_screened)
		printf("  screened: %d frames with the Moon within %.0f deg or the Earth limb within %.0f deg (not fitted)\n",
		       s->n_screened, a->moon_min, a->limb_min);
	printf("  calibration: %.4f +- %.4f DN per photo-e- from %d stars (chi2/dof %.2f)\n",
	       s->dn_per_e, s->dn_per_e_sigma, s->n_cal, s->cal_chi2_dof);
	printf("  %7s %11s %10s %11s %9s %6s %8s\n", "theta", "alpha_px",
	       "sigma", "model", "grad_dir", "stars", "resid");
	for (i = 0; i < n; i++)
		printf("  %7.2f %11.4g %10.3g %11.4g %9.1f %3d/%-3d %7.2f\n",
		       p[i].theta_deg, p[i].alpha_px, p[i].sigma, p[i].model,
		       f[i].grad_dir_deg, f[i].n_match, f[i].n_pred,
		       f[i].resid_px);
	printf("  scale alpha_px / alpha_model = %.4g +- %.2g (stat %.2g); shape chi2/dof %.2f%s\n",
	       s->scale, s->scale_sigma, s->scale_sigma_stat, s->chi2_dof,
	       s->chi2_dof > 4.0 ? "  (the model's SHAPE disagrees: stray diagnose --out curve)" : "");
	printf("  scale / model k_px (%.4g) = %.4f +- %.4f%s\n", s->k_px_model,
	       s->scale_over_kpx, s->scale_over_kpx_sigma,
	       fabs(s->scale_over_kpx - 1.0) > 3.0 * s->scale_over_kpx_sigma ?
	       "  (the model's absolute level is off)" : "  (consistent)");
}

int cmd_flightcheck(int argc, char **argv)
{
	static const struct option opts[] = {
		SENSOR_LONG_OPTIONS,
		NORMALISATION_LONG_OPTION,
		{ "aem", required_argument, NULL, 'a' },
		{ "model", required_argument, NULL, 'm' },
		{ "out", required_argument, NULL, 'o' },
		{ "plot", required_argument, NULL, 'p' },
		{ "catalogue", required_argument, NULL, 'c' },
		{ "oem", required_argument, NULL, 'e' },
		{ "moon-min", required_argument, NULL, 'M' },
		{ "limb-min", required_argument, NULL, 'L' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	struct fc_args a = { 0 };
	struct fc_check_opts o = { 0 };
	struct fc_check c;
	struct fdr_setup su;
	struct stray_error err;
	struct fc_frame *f = NULL;
	struct fc_point *p = NULL;
	struct fc_summary s;
	size_t n = 0;
	int opt, rc;

	fdr_setup_init(&su);
	stray_error_clear(&err);
	a.moon_min = FC_MOON_MIN_DEG;
	a.limb_min = FC_LIMB_MIN_DEG;
	while ((opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 0: continue;
		case 'h': fputs(usage, stdout); return CLI_OK;
		case 'a': a.aem = optarg; continue;
		case 'm': a.model = optarg; continue;
		case 'o': a.out = optarg; continue;
		case 'p': a.plot = optarg; continue;
		case 'c': a.catalogue = optarg; continue;
		case 'e': a.oem = optarg; continue;
		case 'M':
		case 'L':
			if ((rc = cli_parse_double("flightcheck", opt == 'M' ?
					"--moon-min" : "--limb-min", optarg,
					opt == 'M' ? &a.moon_min : &a.limb_min)))
				return rc;
			if (!((opt == 'M' ? a.moon_min : a.limb_min) >= 0.0 &&
			      (opt == 'M' ? a.moon_min : a.limb_min) <= 180.0))
				return cli_usage_error("flightcheck",
					"--moon-min and --limb-min: degrees in [0, 180]");
			continue;
		default: break;
		}
		rc = fdr_setup_option(&su, "flightcheck", opt, optarg);
		if (rc == 0)
			return cli_usage_error("flightcheck", "unknown option");
		if (rc != 1)
			return rc;
	}
	if (optind > argc - 1)
		return cli_usage_error("flightcheck",
				       "FRAMES_DIR or frame files are required");
	a.dir = argv[optind];
	{	/* one operand that is not a folder, or several: frame files */
		struct stat st;

		if (optind < argc - 1 || (stat(a.dir, &st) == 0 &&
					  !S_ISDIR(st.st_mode))) {
			o.files = argv + optind;
			o.n_files = (size_t)(argc - optind);
		}
	}
	if (!a.aem)
		return cli_usage_error("flightcheck", "--aem is required");
	if (!a.model)
		return cli_usage_error("flightcheck", "--model is required");
	if (fdr_setup_load(&su, &err) != STRAY_OK)
		return cli_fail("flightcheck", &err);
	o = (struct fc_check_opts){ a.dir, o.files, o.n_files, a.aem, a.model,
				    a.catalogue, a.oem, a.moon_min, a.limb_min };
	if (fc_check_run(&o, &su, &c, &err) != STRAY_OK)
		return cli_fail("flightcheck", &err);
	f = c.f;
	p = c.p;
	n = c.n;
	s = c.s;
	snprintf(a.cat_name, sizeof(a.cat_name), "%s", c.cat_name);
	if (c.why[0]) {
		/* no number is printed for frames that cannot be calibrated */
		free(f);
		free(p);
		return cli_fail_line("flightcheck", CLI_FAIL, "%s: cannot be "
				     "calibrated: %s", a.dir, c.why);
	}
	rc = STRAY_OK;
	if (a.out) {
		/* the curve file is ordered by angle, as curves are */
		struct fc_point *q = malloc(n * sizeof(*q));

		if (q) {
			memcpy(q, p, n * sizeof(*q));
			qsort(q, n, sizeof(*q), cmp_theta);
			rc = fc_write_curve(a.out, q, n, &s, a.cat_name, &err);
			if (!rc && a.plot)
				rc = plot(a.plot, q, n, &s, &err);
			free(q);
		} else {
			rc = stray_error_set(&err, STRAY_ENOMEM, "out", "out of memory");
		}
	} else if (a.plot) {
		qsort(p, n, sizeof(*p), cmp_theta);
		rc = plot(a.plot, p, n, &s, &err);
	}
	if (rc == STRAY_OK)
		rc = cli.json ? emit_json(&a, f, p, n, &s) : (print_text(&a, f, p, n, &s), CLI_OK);
	else
		rc = cli_fail("flightcheck", &err);
	free(f);
	free(p);
	return rc;
}
