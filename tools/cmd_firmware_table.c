/*
 * cmd_firmware_table.c - `stray firmware-table`: the flight table of
 * firmware_fdr from a system attenuation curve and a sensor, as const C
 * source (for flash) and as a binary blob (for upload), both sealed with
 * the CRC-32 the module checks at init (issue #6, firmware_fdr/README.md).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "fdr_options.h"
#include "fdrfw/table_build.h"
#include "stray/curve_io.h"
#include "stray/errfmt.h"
#include "stray/file.h"

static const char usage[] =
	"usage: stray firmware-table --curve C.csv [--out-c F.c] [--out-bin F.bin]\n"
	"                            [--name SYMBOL] [--rate R] [--hysteresis-deg H]\n"
	"                            [--earth-albedo A] [--json] [options]\n"
	"\n"
	"The flight table of firmware_fdr: the curve as log10 alpha with its\n"
	"exclusion envelope, the sensor's FDR constants, the detection threshold\n"
	"and the reference fluxes, sealed with a CRC-32.\n"
	"\n"
	"  --curve C.csv       system attenuation curve (required, <= 128 rows)\n"
	"  --out-c F.c         write the table as const C source\n"
	"  --out-bin F.bin     write the table as a little-endian blob\n"
	"  --name SYMBOL       C name of the table (default fdrfw_flight_table)\n"
	"  --rate R            tolerated false stars per image (sensor's default)\n"
	"  --hysteresis-deg H  flags clear H deg past the edge (default 0.5)\n"
	"  --earth-albedo A    Lambertian albedo of the Earth (default 0.3)\n"
	"  --json              machine-readable summary\n"
	SENSOR_USAGE NORMALISATION_USAGE DETECTOR_USAGE
	"                      thesis flies eq. 2.18 on board; the others fly\n"
	"                      their validated models as a grid over the\n"
	"                      background (table version 3, nominal exposure)\n";

struct ft_args {
	const char *curve, *out_c, *out_bin, *name;
	double rate, hysteresis_deg, albedo;
};

/* The table's symbol goes into C source: [A-Za-z_][A-Za-z0-9_]*. */
static int c_identifier(const char *name)
{
	size_t i;

	if (!name)
		return 1;	/* the default */
	for (i = 0; name[i]; i++) {
		char ch = name[i];

		if (!(ch == '_' || (ch >= 'a' && ch <= 'z') ||
		      (ch >= 'A' && ch <= 'Z') || (i > 0 && ch >= '0' && ch <= '9')))
			return 0;
	}
	return i > 0 && i < 64;
}

static int parse_args(int argc, char **argv, struct fdr_setup *s,
		      struct ft_args *a)
{
	static const struct option opts[] = {
		{ "help", no_argument, NULL, 'h' },
		{ "json", no_argument, &cli.json, 1 },
		{ "curve", required_argument, NULL, 'c' },
		{ "out-c", required_argument, NULL, 'C' },
		{ "out-bin", required_argument, NULL, 'B' },
		{ "name", required_argument, NULL, 'n' },
		{ "rate", required_argument, NULL, 'r' },
		{ "hysteresis-deg", required_argument, NULL, 'H' },
		{ "earth-albedo", required_argument, NULL, 'e' },
		SENSOR_LONG_OPTIONS,
		NORMALISATION_LONG_OPTION,
		DETECTOR_LONG_OPTIONS,
		{ NULL, 0, NULL, 0 }
	};
	const char *cmd = "firmware-table";
	int opt, rc = CLI_OK;

	optind = 1;
	while (rc == CLI_OK &&
	       (opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 0: break;
		case 'h': fputs(usage, stdout); return -1;
		case 'c': a->curve = optarg; break;
		case 'C': a->out_c = optarg; break;
		case 'B': a->out_bin = optarg; break;
		case 'n': a->name = optarg; break;
		case 'r': rc = cli_parse_double(cmd, "rate", optarg, &a->rate); break;
		case 'H':
			rc = cli_parse_double(cmd, "hysteresis-deg", optarg,
					      &a->hysteresis_deg);
			break;
		case 'e':
			rc = cli_parse_double(cmd, "earth-albedo", optarg,
					      &a->albedo);
			break;
		case '?':
			return cli_usage_error(cmd, "unknown option '%s'",
					       argv[optind - 1]);
		default:
			rc = fdr_setup_option(s, cmd, opt, optarg);
			rc = rc == 1 ? CLI_OK : rc ? rc : CLI_USAGE;
		}
	}
	if (rc != CLI_OK)
		return rc;
	if (optind < argc)
		return cli_usage_error(cmd, "unexpected argument '%s'",
				       argv[optind]);
	if (!a->curve)
		return cli_usage_error(cmd, "--curve is required");
	if (!c_identifier(a->name))
		return cli_usage_error(cmd, "option '--name': '%s' is not a C "
				       "identifier ([A-Za-z_][A-Za-z0-9_]*, "
				       "at most 63 characters)", a->name);
	if (!a->out_c && !a->out_bin && !cli.json)
		return cli_usage_error(cmd, "nothing to do: give --out-c, "
				       "--out-bin or --json");
	if (a->rate <= 0.0)
		return cli_usage_error(cmd, "option '--rate': must be > 0");
	return CLI_OK;
}

/* Both outputs are written to temporaries first and renamed only when
 * both are whole, so a failed run leaves neither. */
static int write_outputs(const struct ft_args *a, const struct fdrfw_table *t,
			 struct stray_error *err)
{
	static uint8_t blob[FDRFW_BLOB_SIZE];
	struct stray_file_out oc, ob;
	int rc = STRAY_OK;

	oc.f = ob.f = NULL;
	oc.tmp[0] = ob.tmp[0] = '\0';
	if (a->out_c &&
	    (rc = stray_file_open_atomic(&oc, a->out_c, err)) == STRAY_OK &&
	    fdrfw_table_write_c(oc.f, t, a->name) != 0)
		rc = stray_error_set(err, STRAY_EIO, "out-c",
				     "could not write the C source");
	if (rc == STRAY_OK && a->out_bin) {
		fdrfw_table_serialize(t, blob);
		if ((rc = stray_file_open_atomic(&ob, a->out_bin, err)) ==
		    STRAY_OK && fwrite(blob, 1, sizeof(blob), ob.f) != sizeof(blob))
			rc = stray_error_set(err, STRAY_EIO, "out-bin",
					     "could not write the blob");
	}
	if (rc == STRAY_OK && a->out_c)
		rc = stray_file_commit(&oc, err);
	if (rc == STRAY_OK && a->out_bin)
		rc = stray_file_commit(&ob, err);
	if (rc != STRAY_OK) {
		stray_file_abort(&oc);
		stray_file_abort(&ob);
	}
	return rc;
}

static int print_summary(const struct ft_args *a, const struct fdrfw_table *t,
			 const struct stray_exclusion *sun,
			 const struct fdrfw_thin_report *thin)
{
	if (thin->rows_in != thin->rows_out && !cli.json)
		printf("curve thinned from %zu to %zu rows for the table: "
		       "largest change %.3g in log10 alpha, at %.2f deg\n",
		       thin->rows_in, thin->rows_out, thin->max_err_dex,
		       thin->at_deg);
	if (cli.json) {
		cJSON *o = cJSON_CreateObject();

		cJSON_AddItemToObject(o, "curve_rows", cJSON_CreateNumber(
				      (double)thin->rows_in));
		if (thin->rows_in != thin->rows_out) {
			cJSON_AddItemToObject(o, "thinned_max_log10_error",
				cli_json_number(thin->max_err_dex));
			cJSON_AddItemToObject(o, "thinned_max_error_at_deg",
				cli_json_number(thin->at_deg));
		}

		cJSON_AddItemToObject(o, "n_curve", cJSON_CreateNumber(t->n_curve));
		cJSON_AddItemToObject(o, "blob_bytes",
				      cJSON_CreateNumber(FDRFW_BLOB_SIZE));
		cJSON_AddItemToObject(o, "crc32", cJSON_CreateNumber(t->crc32));
		cJSON_AddStringToObject(o, "normalisation",
			fdrfw_table_is_thesis(t) ? "thesis" : "consistent");
		cJSON_AddItemToObject(o, "k_px", cli_json_number((double)t->k_px));
		cJSON_AddItemToObject(o, "table_version",
				      cJSON_CreateNumber(t->version));
		cJSON_AddStringToObject(o, "detector",
					fdrfw_table_detector_name(t));
		if (t->detector == STRAY_DET_TETRA3)
			cJSON_AddItemToObject(o, "detector_sigma",
				cli_json_number((double)t->detector_sigma));
		cJSON_AddStringToObject(o, "binding", stray_failure_mode_name(
					fdrfw_table_binding(t)));
		cJSON_AddItemToObject(o, "detector_grid_nodes",
				      cJSON_CreateNumber(t->n_det));
		cJSON_AddItemToObject(o, "threshold_e",
				      cli_json_number((double)t->i_sdt_e));
		cJSON_AddItemToObject(o, "alpha_required_sun",
				      cli_json_number((double)t->alpha_req_sun));
		/* libstray's verdict, as `stray exclusion` gives it; the
		 * table's own field apart (firmware_fdr/README.md) */
		cJSON_AddItemToObject(o, "sun_deg", cli_json_number(
			sun->excluded ? (double)t->exclusion_sun_deg : NAN));
		cJSON_AddBoolToObject(o, "sun_excluded", sun->excluded);
		if (!sun->excluded)
			cJSON_AddStringToObject(o, "reason", sun->reason);
		cJSON_AddItemToObject(o, "table_exclusion_sun_deg",
				      cli_json_number((double)t->exclusion_sun_deg));
		cJSON_AddItemToObject(o, "hysteresis_deg",
				      cli_json_number((double)t->hysteresis_deg));
		return cli_json_emit(o);
	}
	printf("flight table from %s: %lu angles, %lu bytes, CRC-32 0x%08lX\n"
	       "  normalisation %s, k_px %.4g (eq. 2.3)\n"
	       "  detector %s (%s bind the Sun's angle)\n"
	       "  threshold I_sdt %.6g e-, Sun alpha_required %.4g, "
	       "exclusion %.3f deg (hysteresis %.2f deg)\n",
	       a->curve, (unsigned long)t->n_curve,
	       (unsigned long)FDRFW_BLOB_SIZE, (unsigned long)t->crc32,
	       fdrfw_table_is_thesis(t) ? "thesis" : "consistent",
	       (double)t->k_px, fdrfw_table_detector_name(t),
	       fdrfw_table_binding(t) == STRAY_FAIL_LOST_STARS ?
	       "lost stars" : "false stars",
	       (double)t->i_sdt_e, (double)t->alpha_req_sun,
	       (double)t->exclusion_sun_deg, (double)t->hysteresis_deg);
	if (!sun->excluded)
		printf("  Sun not excluded by the baffle: %s; the table carries "
		       "%.3f deg (the Sun blinds the tracker wherever it is in "
		       "front of the aperture plane)\n", sun->reason,
		       (double)t->exclusion_sun_deg);
	return CLI_OK;
}

int cmd_firmware_table(int argc, char **argv)
{
	static struct fdrfw_table t;
	struct ft_args a = { NULL, NULL, NULL, "fdrfw_flight_table", NAN,
			     FDRFW_BUILD_HYSTERESIS_DEG, FDRFW_BUILD_ALBEDO };
	struct fdrfw_build_params p;
	struct fdr_setup s;
	struct stray_curve c;
	struct stray_curve_view v;
	struct stray_exclusion sun;
	struct fdrfw_thin_report thin;
	struct stray_error err;
	int rc;

	fdr_setup_init(&s);
	stray_error_clear(&err);
	rc = parse_args(argc, argv, &s, &a);
	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	if (fdr_setup_load(&s, &err) != STRAY_OK)
		return cli_fail("firmware-table", &err);
	if (stray_curve_load(a.curve, &c, &err) != STRAY_OK)
		return cli_fail("firmware-table", &err);
	p.f_sun_ph_s_m2 = s.flux.sun;
	p.f_moon_full_ph_s_m2 = s.flux.moon;
	p.f_drs_ph_s_m2 = s.flux.drs;
	p.rate = isnan(a.rate) ? 0.0 : a.rate;
	p.hysteresis_deg = a.hysteresis_deg;
	p.earth_albedo = a.albedo;
	p.normalisation = s.normalisation;
	/* the named detector's models go into the table (issue 28) */
	p.detector = s.detector;
	p.detector_sigma = s.detector_sigma;
	v = stray_curve_view_of(&c);
	rc = fdrfw_table_build_thinned(&v, &s.sensor, &p, &t, &sun, &thin,
					&err);
	stray_curve_free(&c);
	if (rc == STRAY_OK)
		rc = write_outputs(&a, &t, &err);
	if (rc != STRAY_OK) {
		if (!err.file[0])
			stray_error_locate(&err, a.curve, 0);
		return cli_fail("firmware-table", &err);
	}
	return print_summary(&a, &t, &sun, &thin);
}
