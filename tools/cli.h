/*
 * cli.h - what every `stray` subcommand shares: the global options, the
 * one-line error path, exit codes (docs/cli.md: 0 ok, 1 failure, 2 bad
 * input) and --json output through cJSON.
 */
#ifndef STRAY_TOOLS_CLI_H
#define STRAY_TOOLS_CLI_H

#include <cJSON.h>

#include "stray/error.h"
#include "tools/entry.h"	/* enum cli_exit, cli_set_prog */

struct cli_global {
	int json;		/* --json: machine-readable stdout */
	const char *prog;	/* "stray" */
};

extern struct cli_global cli;

/* Print err as one line on stderr, "stray <cmd>: ...", and return 1 or 2. */
int cli_fail(const char *cmd, const struct stray_error *err);

/* A failure whose reason is text, not a stray_error: the one line
 * "stray <cmd>: <msg>" (stderr, or the library call's error); returns
 * code (1 or 2). */
int cli_fail_line(const char *cmd, int code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* A note the caller should see beside a result (not an error: the
 * command goes on), "stray <cmd>: <msg>": on stderr, or kept among the
 * library call's notes (stray_api_notes; Python warns with each). */
void cli_note(const char *cmd, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* A usage error: print "stray <cmd>: <msg>" and a hint; return 2. */
int cli_usage_error(const char *cmd, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* Parse a finite double option value; on failure print and return 2. */
int cli_parse_double(const char *cmd, const char *opt, const char *text,
		     double *out);

/* Parse a whole number in [lo, hi]; on failure print and return 2. */
int cli_parse_count(const char *cmd, const char *opt, const char *text,
		    double lo, double hi, double *out);

/*
 * One step of a subcommand's getopt_long loop (short options: "h"):
 * *opt = the next option, flags (0) skipped, or -1 when none is left;
 * --help prints usage and returns -1; an unknown option is a usage error
 * (2).  CLI_OK otherwise.
 */
struct option;
int cli_next_option(const char *cmd, int argc, char **argv,
		    const struct option *opts, const char *usage, int *opt);

/* After the options: any operand left is a usage error (2). */
int cli_no_operands(const char *cmd, int argc, char **argv);

/* Print a JSON object to stdout (pretty) and free it; returns 0 or 1. */
int cli_json_emit(cJSON *obj);

/* A JSON number, or null where v is not finite (JSON has no inf/nan). */
cJSON *cli_json_number(double v);


#endif /* STRAY_TOOLS_CLI_H */
