/*
 * commands.h - the subcommands of `stray`, one file each (cmd_<name>.c).
 * To add one: declare it here and add a row to the table in stray.c.
 * The commands that trace take a runner and are declared in the public
 * tools/entry.h (stray-mpi runs them too).
 */
#ifndef STRAY_TOOLS_COMMANDS_H
#define STRAY_TOOLS_COMMANDS_H

#include "tools/entry.h"

struct cmd {
	const char *name;
	int (*run)(int argc, char **argv);	/* argv[0] is the name */
	const char *summary;
};

int cmd_photometry(int argc, char **argv);
int cmd_fdr(int argc, char **argv);
int cmd_exclusion(int argc, char **argv);
int cmd_report(int argc, char **argv);
int cmd_photometer(int argc, char **argv);
int cmd_orbit(int argc, char **argv);
int cmd_availability(int argc, char **argv);
int cmd_ccsds(int argc, char **argv);
int cmd_firmware_table(int argc, char **argv);
int cmd_reduce(int argc, char **argv);
int cmd_rig(int argc, char **argv);
int cmd_frames(int argc, char **argv);
int cmd_flightcheck(int argc, char **argv);
int cmd_lens(int argc, char **argv);
int cmd_review(int argc, char **argv);
/* `stray sweep import` (argv[0] "import"); `stray sweep` itself is the
 * design sweep, tools/entry.h */
int cmd_sweep_import(int argc, char **argv);

#endif /* STRAY_TOOLS_COMMANDS_H */
