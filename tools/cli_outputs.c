/*
 * cli_outputs.c - every output of a command compared with every input and
 * with the other outputs right after the command line is read, before a
 * 20-s diagnosis or a sweep runs (issue 31).  The library refuses the same
 * at the moment an output is opened (stray/file.h, file_guard.c); this is
 * the early answer.  Which options name outputs is listed here, one table
 * for all commands; every other word of the command line that names an
 * existing file or folder counts as an input.
 */
#include <limits.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "stray/errfmt.h"
#include "stray/file.h"

struct out_opt {
	const char *cmd;
	const char *const *opts;	/* long names, NULL-terminated */
};

#define OPTS(...) (const char *const[]){ __VA_ARGS__, NULL }

/* Outputs of each command.  Not listed: sweep's --state (its own
 * resumable store, read and written), availability's --plot PREFIX and
 * reduce's --plot-dir DIR (names that files are made from or written
 * into: those files meet the library's check when opened). */
static const struct out_opt table[] = {
	{ "availability", OPTS("out", "write-oem", "write-aem") },
	{ "diagnose", OPTS("plot", "write-model") },
	{ "exclusion", OPTS("plot") },
	{ "fdr", OPTS("plot") },
	{ "firmware-table", OPTS("out-c", "out-bin") },
	{ "flightcheck", OPTS("out", "plot") },
	{ "frames", OPTS("out-dir", "png", "plot") },
	{ "lens", OPTS("out") },
	{ "orbit", OPTS("out", "plot") },
	{ "photometer", OPTS("out") },
	{ "reduce", OPTS("out", "zemax", "map") },
	{ "sweep", OPTS("out", "plot") },
	{ "trace", OPTS("out", "export-obj", "paths-out", "plot",
			"plot-orders", "dump-paths", "map", "focal-map",
			"focal-map-png") },
};

#define MAX_WORDS 256

struct word {
	const char *opt;	/* the option naming it, or NULL */
	const char *path;
	char derived[PATH_MAX];	/* an output named after another */
};

static const char *const *outputs_of(const char *cmd)
{
	size_t i;

	for (i = 0; i < sizeof(table) / sizeof(table[0]); i++)
		if (strcmp(table[i].cmd, cmd) == 0)
			return table[i].opts;
	return NULL;
}

static int is_output(const char *const *outs, const char *name, size_t len)
{
	for (; *outs; outs++)
		if (strlen(*outs) == len && strncmp(*outs, name, len) == 0)
			return 1;
	return 0;
}

/* The file an output option also writes beside its own: diagnose
 * --write-model S.json writes S.obj (diagnose/surfaces.c), --plot F.png
 * writes F-resid.png (tools/plot_diag.c); "" when none. */
static void derive(const char *cmd, const char *opt, const char *path,
		   char *out, size_t size)
{
	const char *dot = strrchr(path, '.');
	int n = -1;

	out[0] = '\0';
	if (strcmp(cmd, "diagnose") != 0)
		return;
	if (!strncmp(opt, "--write-model", 13)) {
		if (!dot || strchr(dot, '/'))
			dot = path + strlen(path);
		n = snprintf(out, size, "%.*s.obj", (int)(dot - path), path);
	} else if (!strncmp(opt, "--plot", 6)) {
		n = snprintf(out, size, "%.*s-resid%s",
			     (int)(dot ? (size_t)(dot - path) : strlen(path)),
			     path, dot ? dot : ".png");
	}
	if (n < 0 || (size_t)n >= size)
		out[0] = '\0';
}

static int same_file(const char *a, const char *b)
{
	struct stat sa, sb;

	return stat(a, &sa) == 0 && stat(b, &sb) == 0 &&
	       (S_ISREG(sa.st_mode) || S_ISDIR(sa.st_mode)) &&
	       sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

static int is_device(const char *p)
{
	struct stat st;

	return stat(p, &st) == 0 && !S_ISREG(st.st_mode) &&
	       !S_ISDIR(st.st_mode);
}

static int refuse(const char *cmd, const char *opt, const char *path,
		  const char *why)
{
	struct stray_error err;

	stray_error_clear(&err);
	stray_error_at(&err, STRAY_EINVAL, path, 0, 0, why);
	if (opt) {	/* "--out=x" names the option "--out" */
		char name[64];
		size_t n = strcspn(opt, "=");

		snprintf(name, sizeof(name), "%.*s", (int)n, opt);
		stray_error_column(&err, name);
	}
	return cli_fail(cmd, &err);
}

int cli_check_outputs(const char *cmd, int argc, char **argv)
{
	static struct word out[MAX_WORDS];
	const char *const *outs = outputs_of(cmd);
	const char *in[MAX_WORDS];
	size_t n_out = 0, n_in = 0, i, j;
	int k;

	if (!outs)
		return CLI_OK;
	for (k = 1; k < argc; k++) {
		const char *a = argv[k], *eq;

		if (strcmp(a, "--") == 0)
			continue;
		if (strncmp(a, "--", 2) == 0) {
			eq = strchr(a, '=');
			if (is_output(outs, a + 2,
				      eq ? (size_t)(eq - a - 2) : strlen(a + 2))) {
				const char *p = eq ? eq + 1 : k + 1 < argc
						? argv[++k] : NULL;

				if (p && n_out < MAX_WORDS) {
					out[n_out].opt = a;
					out[n_out].path = p;
					out[n_out].derived[0] = '\0';
					n_out++;
					if (n_out < MAX_WORDS) {
						out[n_out].opt = a;
						derive(cmd, a, p,
						       out[n_out].derived,
						       PATH_MAX);
						out[n_out].path =
							out[n_out].derived;
						n_out += out[n_out].path[0] != 0;
					}
				}
				continue;
			}
			if (eq && n_in < MAX_WORDS)
				in[n_in++] = eq + 1;
			continue;
		}
		if (n_in < MAX_WORDS)	/* an operand or an option's value */
			in[n_in++] = (eq = strchr(a, '=')) &&
				     access(a, F_OK) != 0 ? eq + 1 : a;
	}
	for (i = 0; i < n_out; i++) {
		char ci[PATH_MAX], cj[PATH_MAX];

		if (is_device(out[i].path))
			continue;
		for (j = 0; j < n_in; j++)
			if (same_file(out[i].path, in[j]))
				return refuse(cmd, out[i].opt, out[i].path,
					"is also an input of this run (the "
					"same file); give the output another name");
		for (j = 0; j < i; j++)
			if (stray_file_canonical(out[i].path, ci, sizeof(ci)) == 0 &&
			    stray_file_canonical(out[j].path, cj, sizeof(cj)) == 0 &&
			    strcmp(ci, cj) == 0)
				return refuse(cmd, out[i].opt, out[i].path,
					      "is named twice as an output "
					      "of this run (the same file)");
	}
	return CLI_OK;
}
