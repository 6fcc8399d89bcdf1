/*
 * dispatch.c - the table of `stray`'s subcommands and how one is run
 * (its outputs all or nothing), shared by the program (stray.c) and the
 * library call that runs a command in-process (api.c, issue 32).
 */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "dispatch.h"
#include "stray/file.h"
#include "tracer/runner.h"

/* The commands that trace, with this process's threads as their runner
 * (stray-mpi passes its MPI farm instead, mpi/stray_mpi.c). */
static int trace_local(int argc, char **argv)
{
	return cmd_trace(argc, argv, &tracer_runner_local);
}

static int diagnose_local(int argc, char **argv)
{
	return cmd_diagnose(argc, argv, &tracer_runner_local);
}

/* `stray sweep import ...` brings in frames taken by other software
 * (cmd_sweep_import.c); any other `stray sweep` is the design sweep,
 * whose options all start with "--", so the word is free. */
static int sweep_local(int argc, char **argv)
{
	if (argc > 1 && strcmp(argv[1], "import") == 0)
		return cmd_sweep_import(argc - 1, argv + 1);
	return cmd_sweep(argc, argv, &tracer_runner_local);
}

static const struct cmd commands[] = {
	{ "photometry", cmd_photometry,
	  "reference photon fluxes in a sensor's passband" },
	{ "fdr", cmd_fdr,
	  "false-detection rate and the attenuation it requires" },
	{ "exclusion", cmd_exclusion,
	  "Sun, Moon and Earth exclusion angles of a curve" },
	{ "report", cmd_report,
	  "design-review report (HTML and Markdown) of a results folder" },
	{ "review", cmd_review,
	  "the design review of your own system from one project file" },
	{ "photometer", cmd_photometer,
	  "virtual photometer sweep of a baffle (noise, floor) from a true curve" },
	{ "firmware-table", cmd_firmware_table, "flight table of firmware_fdr (C source and CRC-sealed blob)" },
	{ "orbit", cmd_orbit, "the flight module along a day of a sun-synchronous orbit" },
	{ "availability", cmd_availability, "tracker availability over a mission (CCSDS OEM/AEM, several heads)" },
	{ "ccsds", cmd_ccsds, "an OEM or AEM as the toolkit reads it (segments, frames, span, states)" },
	{ "trace", trace_local, "attenuation curve of a baffle by Monte Carlo ray tracing" },
	{ "diagnose", diagnose_local, "name the physical causes of a model-measurement discrepancy" },
	{ "lens", cmd_lens, "a lens curve without lab data: the ideal lens, or a PST import" },
	{ "reduce", cmd_reduce, "lens attenuation curve, noise floor and ghosts from a lab sweep" },
	{ "rig", cmd_rig, "control the lab sweep daemon strayrigd" },
	{ "sweep", sweep_local, "Sun exclusion angle over a grid of baffle designs (resumable); 'sweep import': frames of other software into a lab sweep folder" },
	{ "frames", cmd_frames, "rendered frames, star detection and false stars vs the FDR model" },
	{ "flightcheck", cmd_flightcheck, "stray-light curve from flight frames, calibrated on catalogue stars, vs the model" },
};

#define N_COMMANDS (sizeof(commands) / sizeof(commands[0]))

size_t cli_n_commands(void)
{
	return N_COMMANDS;
}

const struct cmd *cli_command(size_t i)
{
	return i < N_COMMANDS ? &commands[i] : NULL;
}

const struct cmd *cli_find_command(const char *name)
{
	size_t i;

	for (i = 0; i < N_COMMANDS; i++)
		if (strcmp(commands[i].name, name) == 0)
			return &commands[i];
	return NULL;
}

/*
 * Commands whose outputs are all written at the end: their files are
 * renamed into place only when the command succeeds (stray/file.h), so a
 * failed run leaves none of them (frames: its --out-dir sweep folder
 * too, stray_dir_open_atomic).  trace and reduce do this themselves;
 * sweep reads its own outputs back and is not deferred.
 */
int cli_run_command(const struct cmd *c, int argc, char **argv)
{
	static const char *const deferred[] = { "photometry", "fdr",
		"exclusion", "photometer", "firmware-table", "orbit",
		"availability", "diagnose", "report", "frames" };
	struct stray_error err;
	size_t i;
	int rc, defer = 0;

	for (i = 0; i < sizeof(deferred) / sizeof(deferred[0]); i++)
		defer |= strcmp(c->name, deferred[i]) == 0;
	/* one run: its outputs may not replace its inputs or each other */
	stray_file_run_begin();
	if ((rc = cli_check_outputs(c->name, argc, argv)) != CLI_OK)
		return rc;
	if (defer)
		stray_file_defer();
	rc = c->run(argc, argv);
	stray_error_clear(&err);
	if (defer && stray_file_finish(rc == CLI_OK, &err) != STRAY_OK &&
	    rc == CLI_OK)
		rc = cli_fail(c->name, &err);
	return rc;
}
