/*
 * stray_mpi.c - `stray-mpi`: `stray trace`, `stray sweep` and `stray
 * diagnose` with their traces spread over MPI ranks (farm.h).
 *
 *   mpirun -n 4 stray-mpi trace --scene ref4 --out c.csv
 *   mpirun -n 4 stray-mpi sweep --scene ref4 --grid edge_radius=0,0.05 ...
 *   mpirun -n 4 stray-mpi diagnose measured.csv --scene ref4 ...
 *   stray-mpi trace ...      (no mpirun: a singleton, one rank)
 *
 * A binary of its own rather than MPI inside `stray`: MPI_Init starts
 * Open MPI's runtime (slow, and its allocations are reported as leaks by
 * LeakSanitizer, which would fail every `stray` test of the sanitizer
 * pass), and `stray` stays installable where there is no MPI.
 * Rank 0 runs the command with the farm as its runner (tracer/runner.h,
 * the commands' entry points in tools/entry.h); the others serve pieces
 * until it is done.
 */
#include <getopt.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "farm.h"
#include "stray/file.h"
#include "stray/provenance.h"
#include "tools/entry.h"
#include "tracer/runner.h"

static const char usage[] =
	"usage: mpirun -n N stray-mpi [--angle-chunks K] [--task-timeout S]\n"
	"                             trace|sweep|diagnose [<args>]\n"
	"\n"
	"  trace, sweep,       as 'stray trace', 'stray sweep' and 'stray\n"
	"  diagnose            diagnose', the traces spread over the ranks;\n"
	"                      same seed, same bits\n"
	"  --angle-chunks K    split each batch's angles in K pieces\n"
	"                      (default: only when batches < 4 x ranks)\n"
	"  --task-timeout S    a rank silent for S s with work is lost: abort\n"
	"                      with one line (default 300)\n"
	"  --stats             after each trace, one stderr line: pieces, bytes\n"
	"                      per piece, pieces done by other ranks\n";

static int usage_error(const char *what, const char *text)
{
	fprintf(stderr, "stray-mpi: %s%s (see 'stray-mpi --help')\n", what,
		text);
	return CLI_USAGE;
}

/* A number in [lo, hi] (an integer when integral), or -1. */
static double parse_number(const char *text, double lo, double hi,
			   int integral)
{
	char *end;
	double v = strtod(text, &end);

	if (end == text || *end != '\0' || !(v >= lo && v <= hi) ||
	    (integral && v != (int)v))
		return -1.0;
	return v;
}

/* The farm runner's context: print its traffic after each trace. */
struct farm_run {
	int show_stats;
};

static int parse_global(int argc, char **argv, struct farm_run *fr)
{
	static const struct option opts[] = {
		{ "angle-chunks", required_argument, NULL, 'c' },
		{ "task-timeout", required_argument, NULL, 't' },
		{ "stats", no_argument, NULL, 's' },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	double v;
	int opt;

	opterr = 0;
	while ((opt = getopt_long(argc, argv, "+h", opts, NULL)) != -1) {
		if (opt == 'h') {
			fputs(usage, stdout);
			return -1;
		}
		if (opt == 's') {
			fr->show_stats = 1;
			continue;
		}
		if (opt != 'c' && opt != 't')
			return usage_error("unknown option ", argv[optind - 1]);
		v = opt == 'c' ? parse_number(optarg, 1, 4096, 1) :
		    parse_number(optarg, 1e-3, 1e6, 0);
		if (v < 0.0)
			return usage_error(opt == 'c' ?
				"--angle-chunks must be an integer in [1, 4096]: " :
				"--task-timeout must be in [0.001, 1e6] s: ", optarg);
		if (opt == 'c')
			farm_config.angle_chunks = (int)v;
		else
			farm_config.task_timeout_s = v;
	}
	if (optind >= argc)
		return usage_error("give a command: trace, sweep or diagnose",
				   "");
	return CLI_OK;
}

/* Its traffic on stderr with --stats (make bench reads it). */
static void print_stats(const struct farm_run *fr, double seconds)
{
	int size;

	MPI_Comm_size(MPI_COMM_WORLD, &size);
	if (!fr->show_stats || !farm_last.tasks)
		return;
	fprintf(stderr, "stray-mpi: stats: ranks %d pieces %llu "
		"remote_pieces %llu bytes_per_remote_piece %.1f "
		"pilot_pieces %llu pilot_bytes_per_remote_piece %.1f "
		"job_bytes %llu scene_builds %llu rank0_build_s %.4f "
		"rank0_done_s %.4f rank0_start_s %.4f seconds %.4f\n", size,
		(unsigned long long)farm_last.tasks,
		(unsigned long long)farm_last.remote_tasks,
		farm_last.remote_tasks ? (double)farm_last.task_bytes /
		farm_last.remote_tasks : 0.0,
		(unsigned long long)farm_last.pilot_tasks,
		farm_last.remote_pilot ? (double)farm_last.pilot_bytes /
		farm_last.remote_pilot : 0.0,
		(unsigned long long)farm_last.job_bytes,
		(unsigned long long)(farm_last.scene_builds +
				     farm_last.local_builds),
		farm_last.local_build_s, farm_last.done_s, farm_last.start_s,
		seconds);
}

/* The runner: the farm. */
static int run_on_farm(void *ctx, const struct tracer_scene_spec *spec,
		       const struct tracer_scene *s,
		       const struct tracer_trace_opts *o,
		       struct tracer_result *res, struct stray_error *err)
{
	int rc = farm_trace(spec, s, o, res, err);

	if (!rc)
		print_stats(ctx, res->seconds);
	return rc;
}

/* A set of traces (a sweep's designs) farmed together. */
static int run_set_on_farm(void *ctx, const struct tracer_trace_item *items,
			   size_t n, tracer_item_done_fn done, void *user,
			   struct stray_error *err)
{
	double t0 = MPI_Wtime();
	int rc = farm_trace_set(items, n, done, user, err);

	if (!rc)
		print_stats(ctx, MPI_Wtime() - t0);
	return rc;
}

static int run_command(int argc, char **argv)
{
	struct farm_run fr = { 0 };
	const struct tracer_runner farm = { run_on_farm, &fr,
					    run_set_on_farm };
	int rc = parse_global(argc, argv, &fr);
	int (*cmd)(int, char **, const struct tracer_runner *) = NULL;

	if (rc)
		return rc < 0 ? CLI_OK : rc;
	if (strcmp(argv[optind], "trace") == 0)
		cmd = cmd_trace;
	else if (strcmp(argv[optind], "sweep") == 0)
		cmd = cmd_sweep;
	else if (strcmp(argv[optind], "diagnose") == 0) {
		cmd = cmd_diagnose;
		/* its path records are read in key order (trace_cache.c) */
		farm_config.paths_any_order = 1;
	} else
		return usage_error("not distributed (use trace, sweep or "
				   "diagnose): ", argv[optind]);
	argc -= optind;
	argv += optind;
	optind = 0;
	/* as `stray` does: no output may replace an input or another */
	stray_file_run_begin();
	if ((rc = cli_check_outputs(argv[0], argc, argv)) != CLI_OK)
		return rc;
	optind = 0;	/* the check parsed argv too */
	return cmd(argc, argv, &farm);
}

int main(int argc, char **argv)
{
	int provided, rank, rc = 0;

	if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) !=
	    MPI_SUCCESS) {
		fputs("stray-mpi: MPI_Init failed\n", stderr);
		return CLI_FAIL;
	}
	MPI_Comm_rank(MPI_COMM_WORLD, &rank);
	cli_set_prog("stray-mpi");
	stray_provenance_set(argc, argv);
	if (rank != 0) {
		rc = farm_serve();
	} else {
		rc = run_command(argc, argv);
		if (fflush(stdout) != 0 && !rc)
			rc = CLI_FAIL;
		if (farm_broken())	/* a rank is lost or busy: end them all */
			MPI_Abort(MPI_COMM_WORLD, rc ? rc : CLI_FAIL);
		farm_quit();
	}
	MPI_Finalize();
	return rc;
}
