/*
 * cmd_orbit.c - `stray orbit`: run the flight module (firmware_fdr) frame
 * by frame along a day of a sun-synchronous orbit, the tracker pointing
 * anti-nadir, and report how often each body excludes the sensor, the
 * false stars it predicts and whether its flags chatter.
 */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "fdrfw/fdrfw.h"
#include "fdrfw/table_build.h"
#include "mission/flight_table.h"
#include "mission/orbit_fly.h"
#include "plot.h"
#include "stray/errfmt.h"
#include "stray/file.h"

static const char usage[] =
	"usage: stray orbit --table F.bin [--epoch YYYY-MM-DD] [--hours H]\n"
	"                   [--step-s S] [--altitude-km A] [--ltan-h L]\n"
	"                   [--out F.csv] [--plot PREFIX]\n"
	"                   [--normalisation consistent|thesis] [--json]\n"
	"\n"
	"Evaluate the flight module frame by frame along a circular\n"
	"sun-synchronous orbit (J2 nodal regression), tracker boresight at the\n"
	"zenith (anti-nadir), with the module's own Sun and Moon ephemeris.\n"
	"The normalisation of eq. 2.3 (k_px) is the table's.\n"
	"\n"
	"  --table F.bin       flight table (stray firmware-table --out-bin)\n"
	"  --epoch D           start, 00:00 TT of that date (2026-06-21)\n"
	"  --hours H           duration (24)\n"
	"  --step-s S          one frame every S seconds (10)\n"
	"  --altitude-km A     circular altitude (550)\n"
	"  --ltan-h L          local time of the ascending node (22.5)\n"
	"  --out F.csv         the timeline, one row per frame\n"
	"  --plot PREFIX       PREFIX.png (angles) and PREFIX_fdr.png (false stars)\n"
	"  --normalisation N   require a table built with this normalisation\n"
	"                      (stray firmware-table --normalisation N)\n"
	"  --json              machine-readable summary\n";

struct orbit_args {
	const char *table, *out, *plot;
	const char *normalisation;	/* required of the table, or NULL */
	int year, month, day;
	double hours, step_s, altitude_km, ltan_h;
};

static const uint32_t flag_bits[] = {
	FDRFW_SUN_EXCLUDED, FDRFW_MOON_EXCLUDED, FDRFW_EARTH_EXCLUDED,
	FDRFW_SUN_IN_FOV, FDRFW_MOON_IN_FOV, FDRFW_EARTH_IN_FOV,
	FDRFW_SUN_ECLIPSED, FDRFW_INPUT_INVALID,
};
static const char *const flag_names[] = {
	"sun_excluded", "moon_excluded", "earth_excluded", "sun_in_fov",
	"moon_in_fov", "earth_in_fov", "sun_eclipsed", "input_invalid",
};
#define N_FLAGS (sizeof(flag_bits) / sizeof(flag_bits[0]))

static int write_csv(const char *path, const struct orbit_run *r,
		     struct stray_error *err)
{
	struct stray_file_out out;
	size_t i;
	int rc = stray_file_open_atomic(&out, path, err);

	if (rc != STRAY_OK)
		return rc;
	fprintf(out.f, "# stray orbit: firmware_fdr along a sun-synchronous orbit\n"
		"t_h,sun_deg,moon_deg,earth_deg,false_stars,flags\n");
	for (i = 0; i < r->n; i++)
		fprintf(out.f, "%.6f,%.4f,%.4f,%.4f,%.6g,%u\n", r->t_h[i],
			r->theta[0][i], r->theta[1][i], r->theta[2][i],
			r->stars[i], (unsigned)r->flags[i]);
	return stray_file_commit(&out, err);
}

static int plot_run(const char *prefix, const struct orbit_run *r,
		    const struct fdrfw_table *t, struct stray_error *err)
{
	double hx[2] = { 0.0, r->t_h[r->n - 1] }, hy[2], ry[2];
	char p1[4096], p2[4096];
	int rc;

	hy[0] = hy[1] = t->exclusion_sun_deg;
	ry[0] = ry[1] = t->fdr_tolerated;
	snprintf(p1, sizeof(p1), "%s.png", prefix);
	snprintf(p2, sizeof(p2), "%s_fdr.png", prefix);
	{
		const struct plot_series s[] = {
			{ r->t_h, r->theta[0], r->n, NULL, NULL, PLOT_RED, PLOT_LINE, "Sun" },
			{ r->t_h, r->theta[1], r->n, NULL, NULL, PLOT_GREY, PLOT_LINE, "Moon" },
			{ r->t_h, r->theta[2], r->n, NULL, NULL, PLOT_GREEN, PLOT_LINE, "Earth limb" },
			{ hx, hy, 2, NULL, NULL, PLOT_RED, PLOT_DASHED, "Sun exclusion angle" },
		};
		struct plot_spec p = { p1, "Off-axis angles along the orbit (boresight at the zenith)",
			"time [h]", "off-axis angle [deg]", 0, 0, 0.0, NAN, 0.0, 180.0, s, 4, 0 };

		if ((rc = plot_render(&p, err)) != STRAY_OK)
			return rc;
	}
	{
		const struct plot_series s[] = {
			{ r->t_h, r->stars, r->n, NULL, NULL, PLOT_BLUE, PLOT_LINE,
			  "predicted false stars per image" },
			{ hx, ry, 2, NULL, NULL, PLOT_RED, PLOT_DASHED, "tolerated" },
		};
		struct plot_spec p = { p2, "False stars predicted on board",
			"time [h]", "false stars per image", 0, 1, 0.0, NAN,
			1e-6, 1e6, s, 2, 0 };

		return plot_render(&p, err);
	}
}

static const char *table_normalisation(const struct fdrfw_table *t)
{
	return fdrfw_table_is_thesis(t) ? "thesis" : "consistent";
}

/* --normalisation: the table must have been built with it. */
static int normalisation_check(const struct orbit_args *a,
			       const struct fdrfw_table *t,
			       struct stray_error *err)
{
	if (!a->normalisation ||
	    strcmp(a->normalisation, table_normalisation(t)) == 0)
		return STRAY_OK;
	return stray_error_at(err, STRAY_EINVAL, a->table, 0, "k_px",
		strcmp(a->normalisation, "thesis") == 0 ?
		"the table is consistent, not thesis (stray firmware-table "
		"--normalisation thesis)" : "the table is thesis, not "
		"consistent (stray firmware-table --normalisation consistent)");
}

static int summary(const struct orbit_args *a, const struct fdrfw_table *t,
		   const struct orbit_run *r)
{
	size_t i, k, count[N_FLAGS] = { 0 }, toggles = 0;
	double max_stars = 0.0, frac;
	cJSON *o = cJSON_CreateObject(), *fl = cJSON_CreateObject();

	for (i = 0; i < r->n; i++) {
		for (k = 0; k < N_FLAGS; k++)
			count[k] += (r->flags[i] & flag_bits[k]) != 0;
		if (i > 0 && ((r->flags[i] ^ r->flags[i - 1]) & FDRFW_SUN_EXCLUDED))
			toggles++;
		if (r->stars[i] > max_stars)
			max_stars = r->stars[i];
	}
	cJSON_AddNumberToObject(o, "frames", (double)r->n);
	cJSON_AddNumberToObject(o, "hours", a->hours);
	cJSON_AddNumberToObject(o, "step_s", a->step_s);
	cJSON_AddNumberToObject(o, "altitude_km", a->altitude_km);
	cJSON_AddStringToObject(o, "normalisation", table_normalisation(t));
	cJSON_AddItemToObject(o, "k_px", cli_json_number((double)t->k_px));
	/* the detector the table flies (issue 28) */
	cJSON_AddStringToObject(o, "detector", fdrfw_table_detector_name(t));
	cJSON_AddNumberToObject(o, "sun_exclusion_toggles", (double)toggles);
	cJSON_AddNumberToObject(o, "max_false_stars", max_stars);
	for (k = 0; k < N_FLAGS; k++)
		cJSON_AddNumberToObject(fl, flag_names[k], (double)count[k] / r->n);
	cJSON_AddItemToObject(o, "fraction_of_frames", fl);
	if (cli.json)
		return cli_json_emit(o);
	printf("stray orbit: %zu frames over %.1f h at %.0f km\n", r->n,
	       a->hours, a->altitude_km);
	printf("  normalisation %s, k_px %.4g (eq. 2.3, from the table)\n",
	       table_normalisation(t), (double)t->k_px);
	if (t->detector != FDRFW_DET_THESIS)	/* the thesis's text as it was */
		printf("  detector %s (the table's grid of its models)\n",
		       fdrfw_table_detector_name(t));
	for (k = 0; k < N_FLAGS; k++) {
		frac = (double)count[k] / r->n;
		printf("  %-16s %6.2f %% of frames\n", flag_names[k], 100.0 * frac);
	}
	printf("  Sun exclusion switched %zu times; at most %.3g false stars per image\n",
	       toggles, max_stars);
	cJSON_Delete(o);
	return CLI_OK;
}

/* YYYY-MM-DD, a real calendar day in 1935..2065 (no 2026-02-30). */
static int parse_epoch(const char *text, struct orbit_args *a)
{
	static const int mdays[12] = { 31, 28, 31, 30, 31, 30,
				       31, 31, 30, 31, 30, 31 };
	int n = 0, leap;

	if (sscanf(text, "%4d-%2d-%2d%n", &a->year, &a->month, &a->day,
		   &n) != 3 || text[n] != '\0' || a->year < 1935 ||
	    a->year > 2065 || a->month < 1 || a->month > 12)
		return 0;
	leap = a->year % 4 == 0 && (a->year % 100 != 0 || a->year % 400 == 0);
	return a->day >= 1 &&
	       a->day <= mdays[a->month - 1] + (a->month == 2 && leap);
}

static int parse_args(int argc, char **argv, struct orbit_args *a)
{
	static const struct option opts[] = {
		{ "table", required_argument, NULL, 't' },
		{ "epoch", required_argument, NULL, 'e' },
		{ "hours", required_argument, NULL, 'H' },
		{ "step-s", required_argument, NULL, 's' },
		{ "altitude-km", required_argument, NULL, 'a' },
		{ "ltan-h", required_argument, NULL, 'l' },
		{ "out", required_argument, NULL, 'o' },
		{ "plot", required_argument, NULL, 'p' },
		{ "normalisation", required_argument, NULL, 'N' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	int opt, rc = CLI_OK;

	while (rc == CLI_OK && (opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		switch (opt) {
		case 0: break;
		case 'h': fputs(usage, stdout); return -1;
		case 't': a->table = optarg; break;
		case 'o': a->out = optarg; break;
		case 'p': a->plot = optarg; break;
		case 'N':
			if (strcmp(optarg, "consistent") != 0 &&
			    strcmp(optarg, "thesis") != 0)
				return cli_usage_error("orbit", "option '--normalisation': '%s' is not consistent or thesis", optarg);
			a->normalisation = optarg;
			break;
		case 'e':
			if (!parse_epoch(optarg, a))
				return cli_usage_error("orbit", "option '--epoch': '%s' is not a date YYYY-MM-DD in 1935..2065", optarg);
			break;
		case 'H': rc = cli_parse_double("orbit", "hours", optarg, &a->hours); break;
		case 's': rc = cli_parse_double("orbit", "step-s", optarg, &a->step_s); break;
		case 'a': rc = cli_parse_double("orbit", "altitude-km", optarg, &a->altitude_km); break;
		case 'l': rc = cli_parse_double("orbit", "ltan-h", optarg, &a->ltan_h); break;
		default:
			return cli_usage_error("orbit", "unknown option '%s'", argv[optind - 1]);
		}
	}
	if (rc != CLI_OK)
		return rc;
	if (!a->table)
		return cli_usage_error("orbit", "--table is required");
	if (!(a->hours > 0.0 && a->hours <= 24.0 * 30) || !(a->step_s >= 0.1) ||
	    a->hours * 3600.0 / a->step_s > 1e7)
		return cli_usage_error("orbit", "--hours must be in (0, 720] and --step-s >= 0.1, at most 1e7 frames");
	if (!(a->altitude_km >= 200.0 && a->altitude_km <= 2000.0))
		return cli_usage_error("orbit", "option '--altitude-km': %g is outside 200..2000", a->altitude_km);
	if (!(a->ltan_h >= 0.0 && a->ltan_h < 24.0))
		return cli_usage_error("orbit", "option '--ltan-h': %g is outside 0..24", a->ltan_h);
	return CLI_OK;
}

int cmd_orbit(int argc, char **argv)
{
	struct orbit_args a = { NULL, NULL, NULL, NULL, 2026, 6, 21, 24.0,
				10.0, 550.0, 22.5 };
	struct fdrfw_table table;
	struct orbit_fly_opts fo;
	struct orbit_run run;
	struct stray_error err;
	int rc = parse_args(argc, argv, &a);

	if (rc != CLI_OK)
		return rc < 0 ? CLI_OK : rc;
	stray_error_clear(&err);
	if (flight_table_load(a.table, &table, &err) != STRAY_OK ||
	    normalisation_check(&a, &table, &err) != STRAY_OK)
		return cli_fail("orbit", &err);
	fo = (struct orbit_fly_opts){ a.year, a.month, a.day, a.hours,
				      a.step_s, a.altitude_km, a.ltan_h };
	if (orbit_fly(&fo, &table, &run, &err) != STRAY_OK)
		return cli_fail("orbit", &err);
	if ((a.out && write_csv(a.out, &run, &err) != STRAY_OK) ||
	    (a.plot && plot_run(a.plot, &run, &table, &err) != STRAY_OK)) {
		orbit_run_free(&run);
		return cli_fail("orbit", &err);
	}
	rc = summary(&a, &table, &run);
	orbit_run_free(&run);
	return rc;
}
