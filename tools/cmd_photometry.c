/*
 * cmd_photometry.c - `stray photometry`: the reference-flux table of a
 * sensor (thesis table 2.1, eq. 2.1-2.2).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "fdr_options.h"
#include "stray/spectrum_io.h"

static const char usage[] =
	"usage: stray photometry [--sensor S] [--sun F] [--vega F] [--qe F] [--json]\n"
	"\n"
	"Photon fluxes in the sensor's passband (eq. 2.1), Vega fixed at the\n"
	"sensor's vega_mag (eq. 2.2): Sun, full Moon, zero-magnitude reference,\n"
	"Vega and the designed reference star (DRS), in ph s^-1 m^-2.\n"
	"\n"
	SENSOR_USAGE
	"  --json              machine-readable output\n"
	"\nBuilt-in spectra (builtin:NAME):\n";

static void print_usage(void)
{
	const struct stray_builtin_spectrum *b;
	size_t n, i;

	fputs(usage, stdout);
	b = stray_builtin_spectra(&n);
	for (i = 0; i < n; i++)
		printf("  %-34s %s\n", b[i].name, b[i].what);
}

static int print_json(const struct fdr_setup *s)
{
	const struct stray_fluxes *f = &s->flux;
	cJSON *o = cJSON_CreateObject();

	cJSON_AddStringToObject(o, "sensor", s->sensor.name);
	cJSON_AddStringToObject(o, "qe", s->sensor.qe);
	cJSON_AddStringToObject(o, "sun_spectrum", s->sensor.sun);
	cJSON_AddStringToObject(o, "vega_spectrum", s->sensor.vega);
	cJSON_AddItemToObject(o, "sun", cli_json_number(f->sun));
	cJSON_AddItemToObject(o, "moon", cli_json_number(f->moon));
	cJSON_AddItemToObject(o, "zero_mag", cli_json_number(f->zero_mag));
	cJSON_AddItemToObject(o, "vega", cli_json_number(f->vega));
	cJSON_AddItemToObject(o, "drs", cli_json_number(f->drs));
	cJSON_AddItemToObject(o, "sun_mag", cli_json_number(f->sun_mag));
	cJSON_AddItemToObject(o, "moon_mag", cli_json_number(s->sensor.moon_mag));
	cJSON_AddItemToObject(o, "vega_mag", cli_json_number(s->sensor.vega_mag));
	cJSON_AddItemToObject(o, "drs_mag", cli_json_number(s->sensor.drs_mag));
	return cli_json_emit(o);
}

static void print_table(const struct fdr_setup *s)
{
	const struct stray_fluxes *f = &s->flux;
	const struct stray_sensor *n = &s->sensor;

	printf("Reference photon fluxes seen by %s (thesis table 2.1)\n",
	       n->name);
	printf("  QE:   %s%s\n  Sun:  %s\n  Vega: %s\n\n", n->qe,
	       strstr(n->qe, "approx") ? "  (APPROXIMATE curve, not vendor data)"
				       : "", n->sun, n->vega);
	printf("  %-22s %10s   %s\n", "object", "magnitude", "flux [ph/s/m^2]");
	printf("  %-22s %10.3f   %.4e\n", "Sun", f->sun_mag, f->sun);
	printf("  %-22s %10.3f   %.4e\n", "Full Moon", n->moon_mag, f->moon);
	printf("  %-22s %10.3f   %.4e\n", "Reference star (m = 0)", 0.0,
	       f->zero_mag);
	printf("  %-22s %10.3f   %.4e\n", "Vega", n->vega_mag, f->vega);
	printf("  %-22s %10.3f   %.4e\n", "DRS", n->drs_mag, f->drs);
}

int cmd_photometry(int argc, char **argv)
{
	static const struct option opts[] = {
		SENSOR_LONG_OPTIONS,
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	struct fdr_setup s;
	struct stray_error err;
	int opt, rc;

	fdr_setup_init(&s);
	stray_error_clear(&err);
	while ((opt = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
		if (opt == 0)
			continue;
		if (opt == 'h') {
			print_usage();
			return CLI_OK;
		}
		rc = fdr_setup_option(&s, "photometry", opt, optarg);
		if (rc == 0)
			return cli_usage_error("photometry", "unknown option");
		if (rc != 1)
			return rc;
	}
	if (optind < argc)
		return cli_usage_error("photometry", "unexpected argument '%s'",
				       argv[optind]);
	if (fdr_setup_load(&s, &err) != STRAY_OK)
		return cli_fail("photometry", &err);
	if (cli.json)
		return print_json(&s);
	print_table(&s);
	return CLI_OK;
}
