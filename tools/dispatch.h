/*
 * dispatch.h - `stray`'s subcommands by name, and running one as the
 * program does (tools/dispatch.c).
 */
#ifndef STRAY_TOOLS_DISPATCH_H
#define STRAY_TOOLS_DISPATCH_H

#include <stddef.h>

#include "commands.h"

/* The table's rows, in `stray --help` order. */
size_t cli_n_commands(void);
const struct cmd *cli_command(size_t i);

/* The command called name, or NULL. */
const struct cmd *cli_find_command(const char *name);

/*
 * Run c on argv (argv[0] is its name, getopt re-initialised): outputs
 * that are inputs are refused first, and a deferring command's files are
 * renamed into place only when it succeeds.  The exit code.
 */
int cli_run_command(const struct cmd *c, int argc, char **argv);

#endif /* STRAY_TOOLS_DISPATCH_H */
