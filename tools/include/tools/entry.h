/*
 * entry.h - the `stray` command's public face, for a second binary that
 * runs some of its commands differently (`stray-mpi`, mpi/): the exit
 * codes, the program name in messages, and the commands that trace,
 * each taking the runner that carries out its traces (tracer/runner.h).
 * Everything else in tools/ is private to the `stray` command.
 */
#ifndef STRAY_TOOLS_ENTRY_H
#define STRAY_TOOLS_ENTRY_H

struct tracer_runner;

/* Exit codes (docs/cli.md): 0 ok, 1 failure, 2 bad input. */
enum cli_exit { CLI_OK = 0, CLI_FAIL = 1, CLI_USAGE = 2 };

/* The name messages start with ("stray" unless set). */
void cli_set_prog(const char *prog);

/*
 * Before a command runs (cli_outputs.c): an output option naming a file
 * that is also an input of the command line, or another output, is bad
 * input (one line, 2); CLI_OK otherwise.  argv[0] is the command.
 */
int cli_check_outputs(const char *cmd, int argc, char **argv);

/* argv[0] is the command's name; the exit code. */
int cmd_trace(int argc, char **argv, const struct tracer_runner *runner);
int cmd_sweep(int argc, char **argv, const struct tracer_runner *runner);
int cmd_diagnose(int argc, char **argv, const struct tracer_runner *runner);

#endif /* STRAY_TOOLS_ENTRY_H */
