/*
 * cmd_availability.c - `stray availability`: tracker availability over a
 * mission.  The orbit and attitude come from CCSDS OEM/AEM files (the
 * files GMAT, STK, Orekit or Basilisk write); every head is assessed by
 * the flight module (firmware_fdr, the code that flies) at every epoch,
 * with the sunlit Earth's albedo by latitude and season fed to its Earth
 * term on the ground side; statistics per head and for "any head".
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "avail_report.h"
#include "cli.h"
#include "commands.h"
#include "stray/detector.h"
#include "stray/errfmt.h"

static const char usage[] =
	"usage: stray availability --oem O.oem --aem A.aem --heads H.json\n"
	"                          [--step-s S] [--hours H] [--out F.csv]\n"
	"                          [--plot PREFIX] [--iers F] [--json]\n"
	"       stray availability --write-oem O.oem --write-aem A.aem\n"
	"                          [--epoch YYYY-MM-DD] [--hours H] [--gen-step-s S]\n"
	"                          [--altitude-km A] [--ltan HH:MM] [--inclination-deg I]\n"
	"                          [--attitude nadir|inertial|sun] [--heads H.json ...]\n"
	"\n"
	"Fly the flight module of every head along the orbit of an OEM (CCSDS\n"
	"502.0) and the attitude of an AEM (CCSDS 504.0), both in KVN text,\n"
	"interpolated as their headers say, one frame every S seconds over the\n"
	"span both cover; the Earth's albedo by latitude and season is fed to\n"
	"the module's Earth term.  Reports per head and for \"any head\" the\n"
	"fraction of time available and excluded by each body, the outages\n"
	"and the false stars per frame (docs/availability.md).\n"
	"\n"
	"  --oem F, --aem F     orbit and attitude (KVN)\n"
	"  --heads H.json       {\"heads\": [{\"name\": \"A\", \"boresight_body\": [x,y,z],\n"
	"                       \"up_body\": [x,y,z], \"table\": \"A.bin\"}, ...]}; tables\n"
	"                       from stray firmware-table, relative to H.json\n"
	"  --step-s S           one frame every S seconds (10)\n"
	"  --hours H            only the first H hours of the span\n"
	"  --out F.csv          time series, one row per frame\n"
	"  --plot PREFIX        PREFIX_timeline.png, PREFIX_fdr.png and\n"
	"                       PREFIX_sky_<head>.png\n"
	"  --iers F             UT1 - UTC and the pole from an IERS finals table\n"
	"                       (finals2000A.all) for an OEM or AEM in an\n"
	"                       Earth-fixed frame; zero without one\n"
	"  --json               machine-readable summary\n"
	"  --detector D         the tracker's detector (thesis, window, threshold,\n"
	"                       tetra3): every head's table must be built for it\n"
	"                       (stray firmware-table --detector D), else exit 2;\n"
	"                       default: each table's own (thesis unless built so)\n"
	"  --detector-sigma K   tetra3's k sigma the tables must carry (3)\n"
	"  --write-oem F, --write-aem F\n"
	"                       write a mission: a circular orbit at --altitude-km\n"
	"                       (550), sun-synchronous with its node at --ltan\n"
	"                       (22:30) local time, or at --inclination-deg I\n"
	"                       (node at --ltan at the epoch, J2 regression);\n"
	"                       --attitude nadir (with yaw steering, default),\n"
	"                       inertial (the epoch's nadir attitude held) or sun\n"
	"                       (body +z to the Sun, +x equatorial); from 00:00\n"
	"                       UTC of --epoch (2026-06-21) for --hours (24) every\n"
	"                       --gen-step-s (60) s; with --heads what was written\n"
	"                       is flown in the same run (nothing is written if\n"
	"                       it fails)\n";

/* "HH:MM" local time of the ascending node, in hours. */
static int parse_ltan(const char *text, double *h)
{
	int hh, mm, n = 0;

	if (sscanf(text, "%2d:%2d%n", &hh, &mm, &n) != 2 || text[n] ||
	    hh < 0 || hh > 23 || mm < 0 || mm > 59)
		return 0;
	*h = hh + mm / 60.0;
	return 1;
}

static int parse_date(const char *text, struct mission_args *a)
{
	int n = 0;

	return sscanf(text, "%4d-%2d-%2d%n", &a->year, &a->month, &a->day,
		      &n) == 3 && text[n] == '\0' && a->year >= 1972 &&
	       a->year <= 2065 && a->month >= 1 && a->month <= 12 &&
	       a->day >= 1 && a->day <= 31;
}

/* The same file by name, or by device and inode when it exists. */
static int same_file(const char *x, const char *y)
{
	struct stat sx, sy;

	if (!x || !y)
		return 0;
	if (strcmp(x, y) == 0)
		return 1;
	return stat(x, &sx) == 0 && stat(y, &sy) == 0 &&
	       sx.st_dev == sy.st_dev && sx.st_ino == sy.st_ino;
}

/* --write-oem, --write-aem, --heads and --out: no two the same file,
 * checked before anything is written (the OEM would be overwritten by
 * the AEM, or the heads file by a mission). */
static int distinct_outputs(const char *cmd, const struct mission_args *a)
{
	const char *f[4] = { a->write_oem, a->write_aem, a->heads, a->csv };
	static const char *const opt[4] = { "--write-oem", "--write-aem",
					    "--heads", "--out" };
	int i, j;

	for (i = 0; i < 4; i++)
		for (j = i + 1; j < 4; j++)
			if (same_file(f[i], f[j]))
				return cli_usage_error(cmd, "%s and %s are the same file '%s'",
						       opt[i], opt[j], f[j]);
	return CLI_OK;
}

static int parse_args(int argc, char **argv, struct mission_args *a)
{
	static const struct option opts[] = {
		{ "oem", required_argument, NULL, 'o' },
		{ "aem", required_argument, NULL, 'a' },
		{ "heads", required_argument, NULL, 'H' },
		{ "step-s", required_argument, NULL, 's' },
		{ "hours", required_argument, NULL, 'h' + 256 },
		{ "out", required_argument, NULL, 'c' },
		{ "plot", required_argument, NULL, 'p' },
		{ "write-oem", required_argument, NULL, 'O' },
		{ "write-aem", required_argument, NULL, 'A' },
		{ "epoch", required_argument, NULL, 'e' },
		{ "gen-step-s", required_argument, NULL, 'g' },
		{ "iers", required_argument, NULL, 'I' },
		{ "altitude-km", required_argument, NULL, 'k' },
		{ "ltan", required_argument, NULL, 'L' },
		{ "inclination-deg", required_argument, NULL, 'i' },
		{ "attitude", required_argument, NULL, 't' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ "detector", required_argument, NULL, 'd' + 256 },
		{ "detector-sigma", required_argument, NULL, 'D' + 256 },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc = CLI_OK;
	const char *cmd = "availability";
	enum stray_detector_kind kind;

	while (rc == CLI_OK &&
	       (opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 0: break;
		case 'h': fputs(usage, stdout); return -1;
		case 'o': a->oem = optarg; break;
		case 'a': a->aem = optarg; break;
		case 'H': a->heads = optarg; break;
		case 'c': a->csv = optarg; break;
		case 'I': a->iers = optarg; break;
		case 'p': a->plot = optarg; break;
		case 'O': a->write_oem = optarg; break;
		case 'A': a->write_aem = optarg; break;
		case 's': rc = cli_parse_double(cmd, "step-s", optarg, &a->step_s); break;
		case 'h' + 256:
			a->hours_given = 1;
			rc = cli_parse_double(cmd, "hours", optarg, &a->hours);
			break;
		case 'g': rc = cli_parse_double(cmd, "gen-step-s", optarg, &a->gen_step_s); break;
		case 'k': a->orbit_given = 1; rc = cli_parse_double(cmd, "altitude-km", optarg, &a->altitude_km); break;
		case 'i': a->orbit_given = a->incl_given = 1; rc = cli_parse_double(cmd, "inclination-deg", optarg, &a->incl_deg); break;
		case 'L':
			a->orbit_given = 1;
			if (!parse_ltan(optarg, &a->ltan_h))
				return cli_usage_error(cmd, "option '--ltan': '%s' is not a time HH:MM", optarg);
			break;
		case 't':
			a->orbit_given = 1;
			if (strcmp(optarg, "nadir") == 0)
				a->attitude = MISSION_NADIR;
			else if (strcmp(optarg, "inertial") == 0)
				a->attitude = MISSION_INERTIAL;
			else if (strcmp(optarg, "sun") == 0)
				a->attitude = MISSION_SUN;
			else
				return cli_usage_error(cmd, "option '--attitude': '%s' is not nadir, inertial or sun", optarg);
			break;
		case 'd' + 256:
			if (stray_detector_parse(optarg, &kind, NULL) != STRAY_OK)
				return cli_usage_error(cmd, "option '--detector': '%s' is not thesis, window, threshold or tetra3", optarg);
			a->detector = optarg;
			break;
		case 'D' + 256:
			rc = cli_parse_double(cmd, "detector-sigma", optarg,
					      &a->detector_sigma);
			if (rc == CLI_OK && !(a->detector_sigma >= 0.5 &&
					      a->detector_sigma <= 20.0))
				return cli_usage_error(cmd, "option '--detector-sigma': %g is outside 0.5..20", a->detector_sigma);
			break;
		case 'e':
			if (!parse_date(optarg, a))
				return cli_usage_error(cmd, "option '--epoch': '%s' is not a date YYYY-MM-DD in 1972..2065", optarg);
			break;
		default:
			return cli_usage_error(cmd, "unknown option '%s'", argv[optind - 1]);
		}
	}
	if (rc != CLI_OK)
		return rc;
	if (!!a->write_oem != !!a->write_aem)
		return cli_usage_error(cmd, "--write-oem and --write-aem go together");
	if (a->write_oem) {
		/* what is flown is what is written: one pair of files */
		if (a->oem || a->aem)
			return cli_usage_error(cmd, "--oem/--aem and --write-oem/--write-aem: give one pair");
		if ((rc = distinct_outputs(cmd, a)) != CLI_OK)
			return rc;
		a->oem = a->write_oem;
		a->aem = a->write_aem;
	}
	if (!a->write_oem && a->orbit_given)
		return cli_usage_error(cmd, "--altitude-km, --ltan, --inclination-deg and --attitude describe the mission --write-oem/--write-aem writes");
	if (!(a->altitude_km >= 160.0 && a->altitude_km <= 5000.0))
		return cli_usage_error(cmd, "option '--altitude-km': %g is outside 160..5000", a->altitude_km);
	if (a->incl_given && !(a->incl_deg >= 0.0 && a->incl_deg <= 180.0))
		return cli_usage_error(cmd, "option '--inclination-deg': %g is outside 0..180", a->incl_deg);
	if (!a->write_oem && (!a->oem || !a->aem || !a->heads))
		return cli_usage_error(cmd, "--oem, --aem and --heads are required");
	if (!(a->step_s >= 0.1 && a->step_s <= 86400.0))
		return cli_usage_error(cmd, "option '--step-s': %g is outside 0.1..86400", a->step_s);
	if (!(a->gen_step_s >= 1.0 && a->gen_step_s <= 3600.0))
		return cli_usage_error(cmd, "option '--gen-step-s': %g is outside 1..3600", a->gen_step_s);
	if (!(a->hours > 0.0 && a->hours <= 24.0 * 366 * 2))
		return cli_usage_error(cmd, "option '--hours': %g is outside (0, 17568]", a->hours);
	if (a->write_oem && a->hours_given &&
	    a->hours * 3600.0 / a->gen_step_s > 2e6)
		return cli_usage_error(cmd, "--hours / --gen-step-s: more than 2e6 records to write");
	return CLI_OK;
}

int cmd_availability(int argc, char **argv)
{
	struct mission_args a = { 0 };
	struct mission m;
	struct stray_error err;
	int rc;

	a.step_s = 10.0;
	a.gen_step_s = 60.0;
	a.hours = 24.0 * 366 * 2;
	a.year = 2026;
	a.month = 6;
	a.day = 21;
	a.altitude_km = 550.0;	/* the demo's mission unless told */
	a.ltan_h = 22.5;
	a.incl_deg = -1.0;
	a.attitude = MISSION_NADIR;
	a.detector_sigma = 3.0;
	rc = parse_args(argc, argv, &a);
	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	if (a.write_oem) {
		if (!a.hours_given)
			a.hours = 24.0;	/* a day of the demo mission */
		memset(&m, 0, sizeof(m));
		if (mission_write_demo(&a, &m, &err) != STRAY_OK) {
			mission_free(&m);
			return cli_fail("availability", &err);
		}
		if (!a.heads) {
			mission_free(&m);
			if (!cli.json)
				printf("stray availability: wrote %s and %s\n",
				       a.write_oem, a.write_aem);
			return CLI_OK;
		}
	}
	if (!a.write_oem)
		memset(&m, 0, sizeof(m));
	rc = mission_load(&a, &m, &err);
	if (rc == STRAY_OK)
		rc = mission_fly(&a, &m, &err);
	if (rc == STRAY_OK && a.plot)
		rc = mission_plot(&a, &m, &err);
	if (rc != STRAY_OK) {
		mission_free(&m);
		return cli_fail("availability", &err);
	}
	rc = mission_summary(&a, &m);
	mission_free(&m);
	return rc;
}
