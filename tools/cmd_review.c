/*
 * cmd_review.c - `stray review PROJECT.json --out DIR`: the design review
 * of the user's own system (issue 25, docs/review.md).  Thin: the engine
 * (project file, plan, runner, manifest, report) is review/; each step is
 * this binary run again with the command line the report shows, so what
 * the review found is what `stray exclusion`, `stray availability`, ...
 * print when typed by hand, and a step that fails is listed as failed
 * instead of taking the review with it.
 */
#include <getopt.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "review/review.h"
#include "stray/errfmt.h"
#include "stray/file.h"

static const char usage[] =
	"usage: stray review PROJECT.json --out DIR [--resume] [--rays N] [--json]\n"
	"\n"
	"The whole method on the system a project file names (sensor, scene\n"
	"with --set overrides, lens, requirements; optionally a measured curve,\n"
	"a mission and heads; docs/review.md): photometry, FDR, the lens\n"
	"reduced from a lab sweep, the system trace, exclusion angles, the\n"
	"false stars at the required Sun angle, the diagnosis of the measured\n"
	"curve, the flight table, the mission and its availability.  Each step\n"
	"is a stray command run in DIR (its command line is in the report);\n"
	"a step whose inputs are absent is listed as not run, with why.\n"
	"Writes DIR/review.json (verdicts and steps), DIR/report.html,\n"
	"DIR/report.md, DIR/manifest.json and every step's outputs.\n"
	"\n"
	"  --out DIR     output folder (created)\n"
	"  --resume      keep the steps of the last run whose outputs exist and\n"
	"                whose inputs (command line, files' SHA-256) are unchanged\n"
	"  --rays N      detector-side paths of the system trace (1500000; the\n"
	"                diagnosis traces N/5 per model)\n"
	"  --json        print review.json\n"
	"Exit status: 0 every step that could run is done, 1 a step failed\n"
	"(the review is still written), 2 bad input.\n";

static int print_file(const char *dir, const char *name)
{
	char path[PATH_MAX + 64], *text = NULL;
	struct stray_error err;
	size_t len;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	if (stray_file_read(path, &text, &len, &err) != STRAY_OK)
		return cli_fail("review", &err);
	fwrite(text, 1, len, stdout);
	free(text);
	return CLI_OK;
}

int cmd_review(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "out", required_argument, NULL, 'o' },
		{ "resume", no_argument, NULL, 'r' },
		{ "rays", required_argument, NULL, 'n' },
		{ "json", no_argument, &cli.json, 1 },
		{ "help", no_argument, NULL, 'h' },
		{ NULL, 0, NULL, 0 }
	};
	struct review_project *p = malloc(sizeof(*p));
	struct review_plan *plan = calloc(1, sizeof(*plan));
	const char *out = NULL;
	char self[PATH_MAX];
	struct stray_error err;
	double rays = 1500000;
	int opt, rc = CLI_OK, resume = 0, run_rc, wr;
	ssize_t n;

	if (!p || !plan) {
		free(p), free(plan);
		return cli_usage_error("review", "out of memory");
	}
	while (rc == CLI_OK && (rc = cli_next_option("review", argc, argv, opts,
						     usage, &opt)) == CLI_OK && opt != -1) {
		switch (opt) {
		case 'o': out = optarg; break;
		case 'r': resume = 1; break;
		case 'n': rc = cli_parse_count("review", "rays", optarg, 1000, 1e9, &rays); break;
		}
	}
	if (rc != CLI_OK || opt != -1)
		goto done;
	if (optind != argc - 1 || !out) {
		rc = cli_usage_error("review", "give one PROJECT.json and --out DIR");
		goto done;
	}
	stray_error_clear(&err);
	if (review_project_load(argv[optind], p, &err) != STRAY_OK ||
	    review_plan_make(p, (long)rays, plan, &err) != STRAY_OK) {
		rc = cli_fail("review", &err);
		goto done;
	}
	/* the steps run this very binary */
	n = readlink("/proc/self/exe", self, sizeof(self) - 1);
	if (n <= 0) {
		rc = cli_usage_error("review", "cannot find its own binary (/proc/self/exe)");
		goto done;
	}
	self[n] = '\0';
	run_rc = review_run(self, out, p, plan, resume, &err);
	if (run_rc != STRAY_OK && run_rc != STRAY_EIO) {
		rc = cli_fail("review", &err);
		goto done;
	}
	{
		struct stray_error werr;

		stray_error_clear(&werr);
		wr = review_write(out, p, plan, &werr);
		if (wr != STRAY_OK) {
			rc = cli_fail("review", &werr);
			goto done;
		}
	}
	if (cli.json)
		rc = print_file(out, "review.json");
	else
		printf("stray review: %s/report.html, %s/report.md, %s/review.json\n",
		       out, out, out);
	if (run_rc != STRAY_OK)
		rc = cli_fail("review", &err);
done:
	review_plan_free(plan);
	free(plan);
	free(p);
	return rc < 0 ? CLI_OK : rc;
}
