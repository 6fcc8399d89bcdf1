/*
 * fdr_options.c - the sensor and model options the commands share
 * (fdr_options.h), and the setup's part of their --json and text.
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "fdr_options.h"

int fdr_setup_option(struct fdr_setup *s, const char *cmd, int opt,
		     const char *arg)
{
	switch (opt) {
	case 1000: s->sensor_spec = arg; return 1;
	case 1001: s->sun = arg; return 1;
	case 1002: s->vega = arg; return 1;
	case 1003: s->qe = arg; return 1;
	case 1004:
		if (strcmp(arg, "gauss") != 0 && strcmp(arg, "poisson") != 0)
			return cli_usage_error(cmd,
				"option '--noise': '%s' is not gauss or poisson", arg);
		s->poisson = strcmp(arg, "poisson") == 0;
		return 1;
	case 1005: s->detector_noise = 1; return 1;
	case 1006: s->map_path = arg; return 1;
	case 1007:
		if (cli_parse_double(cmd, "moon-phase", arg, &s->moon_phase_deg))
			return CLI_USAGE;
		if (s->moon_phase_deg < 0.0 || s->moon_phase_deg > 180.0)
			return cli_usage_error(cmd,
				"option '--moon-phase': %g is outside 0..180 deg",
				s->moon_phase_deg);
		return 1;
	case 1008:
		return cli_parse_double(cmd, "rate", arg, &s->rate) ? CLI_USAGE : 1;
	case 1009:
		s->earth_given = 1;
		return cli_parse_double(cmd, "earth-albedo", arg,
					&s->earth_albedo) ? CLI_USAGE : 1;
	case 1010:
		return cli_parse_double(cmd, "altitude-km", arg,
					&s->altitude_km) ? CLI_USAGE : 1;
	case 1011:
		if (strcmp(arg, "consistent") != 0 && strcmp(arg, "thesis") != 0)
			return cli_usage_error(cmd,
				"option '--normalisation': '%s' is not consistent or thesis",
				arg);
		s->normalisation = strcmp(arg, "thesis") == 0 ?
			STRAY_NORM_THESIS : STRAY_NORM_CONSISTENT;
		return 1;
	case 1012: {
		enum stray_detector_kind k;

		if (stray_detector_parse(arg, &k, NULL) != STRAY_OK)
			return cli_usage_error(cmd,
				"option '--detector': '%s' is not thesis, window, threshold or tetra3",
				arg);
		s->detector_name = arg;
		return 1;
	}
	case 1013:
		if (cli_parse_double(cmd, "detector-sigma", arg,
				     &s->detector_sigma))
			return CLI_USAGE;
		if (!(s->detector_sigma >= 0.5 && s->detector_sigma <= 20.0))
			return cli_usage_error(cmd,
				"option '--detector-sigma': %g is outside 0.5..20",
				s->detector_sigma);
		return 1;
	default:
		return 0;
	}
}

void fdr_setup_detector_json(const struct fdr_setup *s, cJSON *o)
{
	cJSON_AddStringToObject(o, "detector", stray_detector_name(s->detector));
	if (s->detector == STRAY_DET_TETRA3)
		cJSON_AddItemToObject(o, "detector_sigma",
				      cli_json_number(s->detector_sigma));
}

void fdr_setup_json(const struct fdr_setup *s, cJSON *o)
{
	cJSON_AddStringToObject(o, "normalisation",
				stray_normalisation_name(s->normalisation));
	cJSON_AddItemToObject(o, "k_px", cli_json_number(fdr_setup_k_px(s)));
}

void fdr_setup_print_normalisation(const struct fdr_setup *s)
{
	printf("  normalisation           %s, k_px = %.4g (eq. 2.3; "
	       "docs/normalisation.md)\n",
	       stray_normalisation_name(s->normalisation), fdr_setup_k_px(s));
}
