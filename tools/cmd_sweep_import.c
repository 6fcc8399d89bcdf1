/*
 * cmd_sweep_import.c - `stray sweep import`: frames taken by other
 * software and the lab's log into a sweep folder `stray reduce` reads.
 * Parse, call stray_sweep_import (libstray/sweep/import*.c,
 * stray/sweep_import.h), print.  Every mismatch between the log and the
 * headers is its own line on stderr.
 */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "stray/errfmt.h"
#include "stray/sweep_import.h"

static const char usage[] =
	"usage: stray sweep import --log LOG.csv --out SWEEP_DIR\n"
	"                          [--col0 N --row0 N] [--satlevel DN]\n"
	"                          [--rotator-zero DEG] [--json] FILE_OR_DIR...\n"
	"\n"
	"Frames taken by other software (FITS as INDI/EKOS, N.I.N.A., MaxIm\n"
	"or a camera SDK write them: 16-bit unsigned, BZERO 32768; or 16-bit\n"
	"grey TIFF) and the lab's CSV log into a sweep folder for 'stray\n"
	"reduce'.  The log has a header line and one row per frame file:\n"
	"  file,angle_deg,frametyp,exptime_s,ndtrans[,readback_deg][,filter]\n"
	"  [,date_obs][,monitor]   (frametyp DARK, AMBIENT or FULL; ndtrans\n"
	"  the ND transmission, 1 = none), in the order the frames were taken.\n"
	"Each header is checked against its row (exposure, frame type, filter,\n"
	"read-back angle, time) and every mismatch is reported; a file in the\n"
	"log and not given, or given and not in the log, is one too.  Nothing\n"
	"is written unless all agree.  SWEEP_DIR (new, or an empty folder)\n"
	"gets our frames with the same pixels, manifest.csv, the originals\n"
	"byte for byte in original/ and import.csv (docs/sweep-import.md).\n"
	"\n"
	"  --log LOG.csv      the lab's log (required)\n"
	"  --out SWEEP_DIR    the sweep folder to write (required)\n"
	"  --col0, --row0 N   detector column and row of the frames' first\n"
	"                     pixel (their Bayer phase) where the headers have\n"
	"                     no XORGSUBF/YORGSUBF (default 0, 0)\n"
	"  --satlevel DN      counts at which a pixel saturates where the\n"
	"                     headers have no SATURATE (default 65535)\n"
	"  --rotator-zero DEG ROTATANG at logged angle 0 (default 0)\n";

static const struct option opts[] = {
	{ "log", required_argument, NULL, 'l' },
	{ "out", required_argument, NULL, 'o' },
	{ "col0", required_argument, NULL, 'c' },
	{ "row0", required_argument, NULL, 'r' },
	{ "satlevel", required_argument, NULL, 's' },
	{ "rotator-zero", required_argument, NULL, 'z' },
	{ "json", no_argument, NULL, 'j' },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 }
};

#define CMD "sweep import"

static int parse(int argc, char **argv, struct stray_import_opts *o)
{
	double v;
	int opt, rc, col = 0, row = 0;

	while ((rc = cli_next_option(CMD, argc, argv, opts, usage, &opt)) ==
	       CLI_OK && opt != -1) {
		switch (opt) {
		case 'l': o->log_path = optarg; break;
		case 'o': o->out_dir = optarg; break;
		case 'j': cli.json = 1; break;
		case 'z':
			if (cli_parse_double(CMD, "rotator-zero", optarg, &v))
				return CLI_USAGE;
			o->rotator_zero_deg = v;
			break;
		default:	/* c, r, s: whole numbers */
			if (cli_parse_count(CMD, opt == 'c' ? "col0" : opt ==
					    'r' ? "row0" : "satlevel", optarg,
					    opt == 's' ? 1 : 0, opt == 's' ?
					    65536 : 65535, &v))
				return CLI_USAGE;
			if (opt == 's') {
				o->has_satlevel = 1;
				o->satlevel = (long)v;
			} else if (opt == 'c') {
				col = 1;
				o->col0 = (long)v;
			} else {
				row = 1;
				o->row0 = (long)v;
			}
		}
	}
	if (rc != CLI_OK)
		return rc;	/* -1: --help printed */
	o->has_origin = col || row;
	o->inputs = argv + optind;
	o->n_inputs = (size_t)(argc - optind);
	if (!o->log_path || !o->out_dir || o->n_inputs == 0)
		return cli_usage_error(CMD, "--log, --out and at least one "
				       "frame file or folder are required");
	return CLI_OK;
}

static void on_mismatch(void *ctx, const struct stray_error *e)
{
	char line[1024];

	(void)ctx;
	fprintf(stderr, "%s " CMD ": %s\n", cli.prog,
		stray_error_format(e, line, sizeof(line)));
}

static int print(const struct stray_import_opts *o,
		 const struct stray_import_result *r)
{
	if (cli.json) {
		cJSON *j = cJSON_CreateObject();

		cJSON_AddStringToObject(j, "sweep_dir", o->out_dir);
		cJSON_AddNumberToObject(j, "frames", (double)r->n_frames);
		cJSON_AddNumberToObject(j, "fits", (double)r->n_fits);
		cJSON_AddNumberToObject(j, "tiff", (double)r->n_tiff);
		cJSON_AddNumberToObject(j, "visits", (double)r->n_angles);
		cJSON_AddNumberToObject(j, "dark", (double)r->n_dark);
		cJSON_AddNumberToObject(j, "ambient", (double)r->n_ambient);
		cJSON_AddNumberToObject(j, "full", (double)r->n_full);
		cJSON_AddNumberToObject(j, "rows", (double)r->n_rows);
		cJSON_AddNumberToObject(j, "cols", (double)r->n_cols);
		cJSON_AddNumberToObject(j, "col0", (double)r->col0);
		cJSON_AddNumberToObject(j, "row0", (double)r->row0);
		cJSON_AddNumberToObject(j, "satlevel", (double)r->satlevel);
		cJSON_AddBoolToObject(j, "readback", r->readback);
		cJSON_AddBoolToObject(j, "dated", r->dated);
		cJSON_AddStringToObject(j, "instrument", r->instrume);
		return cli_json_emit(j);
	}
	printf("imported %zu frames (%zu FITS, %zu TIFF) into %s\n"
	       "  %zu angle visits: %zu FULL, %zu AMBIENT, %zu DARK\n"
	       "  window %zu x %zu px from detector column %ld, row %ld; "
	       "SATLEVEL %ld\n"
	       "  read-back angles: %s; times: %s; camera: %s\n",
	       r->n_frames, r->n_fits, r->n_tiff, o->out_dir, r->n_angles,
	       r->n_full, r->n_ambient, r->n_dark, r->n_cols, r->n_rows,
	       r->col0, r->row0, r->satlevel, r->readback ? "yes" : "none",
	       r->dated ? "every frame" : "not every frame (drift by order)",
	       r->instrume[0] ? r->instrume : "not named");
	return CLI_OK;
}

int cmd_sweep_import(int argc, char **argv)
{
	struct stray_import_opts o;
	struct stray_import_result r;
	struct stray_error err;
	int rc;

	memset(&o, 0, sizeof(o));
	o.mismatch = on_mismatch;
	rc = parse(argc, argv, &o);
	if (rc)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	if (stray_sweep_import(&o, &r, &err) != STRAY_OK) {
		/* one mismatch: its own line says it all */
		if (r.n_mismatch == 1)
			return CLI_USAGE;
		return cli_fail(CMD, &err);
	}
	return print(&o, &r);
}
