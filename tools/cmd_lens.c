/*
 * cmd_lens.c - `stray lens ideal|import`: a lens curve without lab data
 * (issue 23 item 3), written in the curve CSV `--lens` takes.  The
 * physics is libstray's (stray/lens_model.h).
 */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "stray/lens_model.h"
#include "stray/sensor_io.h"

static const char usage[] =
	"usage: stray lens ideal (--field DEG | --sensor S) --out L.csv [--json]\n"
	"       stray lens import PST.csv --out L.csv [--theta-col C]\n"
	"                         [--pst-col C] [--pst-input beam|aperture]\n"
	"\n"
	"A lens curve alpha_lens(theta) = P_det(theta) / P_det(0) for a team\n"
	"without a lab sweep, for `stray trace|diagnose|sweep --lens L.csv`.\n"
	"\n"
	"  ideal             the ideal lens: cos^4(theta) inside the field\n"
	"                    (natural vignetting), 0 beyond (no ghosts, no\n"
	"                    scatter); `--lens ideal:DEG` is the same curve\n"
	"  --field DEG       the field half-angle, or --sensor S: its fov_half_deg\n"
	"  import PST.csv    point-source transmittance vs angle from a lens's\n"
	"                    stray-light analysis (FRED, ASAP, Zemax NSC ...),\n"
	"                    CSV with a header; alpha = PST(theta) / PST(0)\n"
	"  --theta-col C     the angle column in deg (default theta_deg)\n"
	"  --pst-col C       the PST column (default pst)\n"
	"  --pst-input beam|aperture\n"
	"                    the PST's input irradiance: across the beam\n"
	"                    (default) or in the aperture plane (then\n"
	"                    alpha = PST cos(theta) / PST(0))\n"
	"  --out L.csv       the lens curve (kind: lens)\n"
	"  --json            print what was written\n";

struct lens_args {
	const char *mode, *in, *out, *sensor;
	const char *theta_col, *pst_col;
	double field;
	enum stray_pst_input input;
};

static int parse(int argc, char **argv, struct lens_args *a)
{
	static const struct option opts[] = {
		{ "field", required_argument, NULL, 'f' },
		{ "sensor", required_argument, NULL, 's' },
		{ "out", required_argument, NULL, 'o' },
		{ "theta-col", required_argument, NULL, 't' },
		{ "pst-col", required_argument, NULL, 'p' },
		{ "pst-input", required_argument, NULL, 'i' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc;

	a->theta_col = "theta_deg";
	a->pst_col = "pst";
	for (;;) {
		rc = cli_next_option("lens", argc, argv, opts, usage, &opt);
		if (rc)
			return rc;	/* -1: --help was printed */
		if (opt == -1)
			break;
		switch (opt) {
		case 'f':
			rc = cli_parse_double("lens", "--field", optarg,
					      &a->field);
			break;
		case 's': a->sensor = optarg; break;
		case 'o': a->out = optarg; break;
		case 't': a->theta_col = optarg; break;
		case 'p': a->pst_col = optarg; break;
		case 'i':
			if (strcmp(optarg, "beam") == 0)
				a->input = STRAY_PST_BEAM;
			else if (strcmp(optarg, "aperture") == 0)
				a->input = STRAY_PST_APERTURE;
			else
				rc = cli_usage_error("lens", "--pst-input "
					"'%s': beam or aperture", optarg);
			break;
		}
		if (rc)
			return rc;
	}
	a->mode = optind < argc ? argv[optind++] : "";
	if (strcmp(a->mode, "import") == 0 && optind < argc)
		a->in = argv[optind++];
	if (strcmp(a->mode, "ideal") && strcmp(a->mode, "import"))
		return cli_usage_error("lens", "say 'ideal' or 'import PST.csv'");
	if (!a->out)
		return cli_usage_error("lens", "--out L.csv is required");
	if (!strcmp(a->mode, "import") && !a->in)
		return cli_usage_error("lens", "import needs the PST file");
	if (!strcmp(a->mode, "ideal") && !a->sensor == !a->field)
		return cli_usage_error("lens", "ideal needs --field DEG or "
				       "--sensor S (one of them)");
	return cli_no_operands("lens", argc, argv);
}

int cmd_lens(int argc, char **argv)
{
	struct lens_args a = { 0 };
	struct stray_curve c = { 0 };
	struct stray_sensor sensor;
	struct stray_error err;
	int rc = parse(argc, argv, &a);

	if (rc)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	if (a.sensor) {
		rc = stray_sensor_load(a.sensor, &sensor, &err);
		a.field = sensor.fov_half_deg;
	}
	if (!rc)
		rc = strcmp(a.mode, "ideal") == 0
		     ? stray_lens_ideal(a.field, &c, &err)
		     : stray_lens_from_pst(a.in, a.theta_col, a.pst_col,
					   a.input, &c, &err);
	if (!rc)
		rc = stray_curve_save(a.out, &c, &err);
	if (!rc && cli.json) {
		cJSON *o = cJSON_CreateObject();

		cJSON_AddStringToObject(o, "out", a.out);
		cJSON_AddStringToObject(o, "model", a.mode);
		if (!strcmp(a.mode, "ideal"))
			cJSON_AddNumberToObject(o, "field_half_deg", a.field);
		cJSON_AddNumberToObject(o, "angles", (double)c.n);
		rc = cli_json_emit(o);
	} else if (!rc)
		printf("wrote %s: lens curve of %zu angles\n", a.out, c.n);
	stray_curve_free(&c);
	return rc ? cli_fail("lens", &err) : CLI_OK;
}
