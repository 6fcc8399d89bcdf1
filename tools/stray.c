/*
 * stray.c - the `stray` command: global options, then a git-style
 * dispatch to one subcommand (git.c's table of builtins, bpftool's
 * getopt_long front end).
 */
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "dispatch.h"
#include "stray/provenance.h"

/* The commands, one line each (dispatch.c's table). */
static void usage(FILE *out)
{
	size_t i;

	fprintf(out, "usage: stray [--json] [--version] [--help] <command> [<args>]\n\n"
		"commands:\n");
	for (i = 0; i < cli_n_commands(); i++)
		fprintf(out, "  %-12s %s\n", cli_command(i)->name,
			cli_command(i)->summary);
	fprintf(out, "\n'stray <command> --help' describes each command.\n");
}

/* Flush stdout and report a failed write (a full disk must not be silent). */
static int finish(int rc)
{
	if (fflush(stdout) != 0 || ferror(stdout)) {
		fprintf(stderr, "stray: error writing to standard output\n");
		return rc ? rc : CLI_FAIL;
	}
	return rc;
}

int main(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "json", no_argument, NULL, 'j' },
		{ "help", no_argument, NULL, 'h' },
		{ "version", no_argument, NULL, 'V' },
		{ NULL, 0, NULL, 0 }
	};
	const struct cmd *c;
	int opt;

	cli.prog = "stray";
	stray_provenance_set(argc, argv);
	opterr = 0;	/* unknown options get our own one-line message */
	/* '+': stop at the first non-option, the subcommand. */
	while ((opt = getopt_long(argc, argv, "+h", opts, NULL)) != -1) {
		switch (opt) {
		case 'j':
			cli.json = 1;
			break;
		case 'h':
			usage(stdout);
			return finish(CLI_OK);
		case 'V':
			printf("stray %s\n", stray_provenance_version());
			return finish(CLI_OK);
		default:
			usage(stderr);
			return CLI_USAGE;
		}
	}
	if (optind >= argc) {
		usage(stderr);
		return CLI_USAGE;
	}
	c = cli_find_command(argv[optind]);
	if (!c) {
		fprintf(stderr, "stray: '%s' is not a stray command; see 'stray --help'\n",
			argv[optind]);
		return CLI_USAGE;
	}
	argc -= optind;
	argv += optind;
	optind = 0;		/* glibc: full re-initialisation for the command */
	return finish(cli_run_command(c, argc, argv));
}
