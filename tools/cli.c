/*
 * cli.c - shared plumbing of the subcommands: errors, numbers, JSON.
 */
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "cli_capture.h"
#include "stray/errfmt.h"
#include "stray/provenance.h"

struct cli_global cli;

void cli_set_prog(const char *prog)
{
	cli.prog = prog;
}

/* The one error line: on stderr, or kept for the library call that runs
 * the command (cli_capture.h). */
static void error_line(const char *line)
{
	if (cli_capture)
		snprintf(cli_capture->err, sizeof(cli_capture->err), "%s",
			 line);
	else
		fprintf(stderr, "%s\n", line);
}

int cli_fail(const char *cmd, const struct stray_error *err)
{
	char line[1024], full[1400];

	if (err->code == STRAY_OK) {	/* a failure that recorded no reason */
		snprintf(full, sizeof(full), "%s %s: failed without a "
			 "recorded reason (please report this)", cli.prog, cmd);
		error_line(full);
		return CLI_FAIL;
	}
	snprintf(full, sizeof(full), "%s %s: %s", cli.prog, cmd,
		 stray_error_format(err, line, sizeof(line)));
	error_line(full);
	return stray_status_is_bad_input(err->code) ? CLI_USAGE : CLI_FAIL;
}

/* "stray <cmd>: <fmt ...>" into full. */
static void command_line(char *full, size_t size, const char *cmd,
			 const char *fmt, va_list ap)
{
	char msg[1024];

	vsnprintf(msg, sizeof(msg), fmt, ap);
	snprintf(full, size, "%s %s: %s", cli.prog, cmd, msg);
}

int cli_fail_line(const char *cmd, int code, const char *fmt, ...)
{
	char full[1400];
	va_list ap;

	va_start(ap, fmt);
	command_line(full, sizeof(full), cmd, fmt, ap);
	va_end(ap);
	error_line(full);
	return code;
}

void cli_note(const char *cmd, const char *fmt, ...)
{
	char full[1400];
	va_list ap;

	va_start(ap, fmt);
	command_line(full, sizeof(full), cmd, fmt, ap);
	va_end(ap);
	if (cli_capture)
		cli_capture_note(full);
	else
		fprintf(stderr, "%s\n", full);
}

int cli_usage_error(const char *cmd, const char *fmt, ...)
{
	char msg[1024], full[1400];
	va_list ap;

	va_start(ap, fmt);
	if (!cli_capture) {	/* `stray`: as long as it is */
		fprintf(stderr, "%s %s: ", cli.prog, cmd);
		vfprintf(stderr, fmt, ap);
		fprintf(stderr, " (see '%s %s --help')\n", cli.prog, cmd);
		va_end(ap);
		return CLI_USAGE;
	}
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	snprintf(full, sizeof(full), "%s %s: %s (see '%s %s --help')",
		 cli.prog, cmd, msg, cli.prog, cmd);
	error_line(full);
	return CLI_USAGE;
}

int cli_parse_double(const char *cmd, const char *opt, const char *text,
		     double *out)
{
	char *end;
	double v = strtod(text, &end);

	if (end == text || *end != '\0' || !isfinite(v))
		return cli_usage_error(cmd, "option '--%s': '%s' is not a finite number",
				       opt, text);
	*out = v;
	return CLI_OK;
}

int cli_parse_count(const char *cmd, const char *opt, const char *text,
		    double lo, double hi, double *out)
{
	if (cli_parse_double(cmd, opt, text, out))
		return CLI_USAGE;
	if (*out < lo || *out > hi || *out != floor(*out))
		return cli_usage_error(cmd, "option '--%s': '%s' must be an integer in [%.0f, %.0f]",
				       opt, text, lo, hi);
	return CLI_OK;
}

int cli_json_emit(cJSON *obj)
{
	char *text;
	cJSON *p = cJSON_CreateObject();

	/* how this output was made (stray/provenance.h) */
	cJSON_AddStringToObject(p, "command", stray_provenance_command());
	cJSON_AddStringToObject(p, "version", stray_provenance_version());
	if (cJSON_IsObject(obj) && !cJSON_HasObjectItem(obj, "provenance"))
		cJSON_AddItemToObject(obj, "provenance", p);
	else
		cJSON_Delete(p);
	if (cli_capture) {	/* a library call: the object itself */
		cJSON_Delete(cli_capture->json);
		cli_capture->json = obj;
		return CLI_OK;
	}
	text = cJSON_Print(obj);
	int rc = CLI_OK;

	if (!text || puts(text) == EOF)
		rc = CLI_FAIL;
	free(text);
	cJSON_Delete(obj);
	return rc;
}

cJSON *cli_json_number(double v)
{
	return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull();
}

int cli_next_option(const char *cmd, int argc, char **argv,
		    const struct option *opts, const char *usage, int *opt)
{
	while ((*opt = getopt_long(argc, argv, "h", opts, NULL)) == 0)
		;	/* a flag, set by getopt_long itself */
	if (*opt == 'h') {
		fputs(usage, stdout);
		return -1;
	}
	if (*opt == '?')
		return cli_usage_error(cmd, "unknown option '%s'",
				       argv[optind - 1]);
	return CLI_OK;
}

int cli_no_operands(const char *cmd, int argc, char **argv)
{
	if (optind < argc)
		return cli_usage_error(cmd, "unexpected argument '%s'",
				       argv[optind]);
	return CLI_OK;
}
