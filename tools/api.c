/*
 * api.c - the `stray` commands as flat C calls (tools/api.h, issue 32):
 * the options object becomes the command line `stray --json <cmd> ...`
 * and the command runs as the program runs it (dispatch.c), with what it
 * prints or writes for its caller kept (cli_capture.h).  One
 * implementation: Python's numbers are the command's numbers.
 */
#include <getopt.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "api_args.h"
#include "cli_capture.h"
#include "dispatch.h"
#include "stray/errfmt.h"
#include "stray/provenance.h"
#include "tools/api.h"
#include "tracer/cancel.h"

struct stray_api_result {
	struct cli_capture cap;
	char *json;		/* cap.json printed, compact */
	char *command;		/* the equivalent command line */
};

/* getopt, the provenance line and the deferred outputs are the
 * process's: one command at a time. */
static pthread_mutex_t api_lock = PTHREAD_MUTEX_INITIALIZER;

static struct stray_api_result *result_new(void)
{
	return calloc(1, sizeof(struct stray_api_result));
}

/* The command, as `stray` runs it, under the lock. */
static int run_locked(struct stray_api_result *r, const struct cmd *c,
		      struct api_args *a)
{
	char **full = malloc((size_t)(a->n + 3) * sizeof(char *));
	int rc;

	if (!full) {
		snprintf(r->cap.err, sizeof(r->cap.err), "stray %s: out of "
			 "memory", a->v[0]);
		return CLI_FAIL;
	}
	full[0] = "stray";
	full[1] = "--json";
	memcpy(full + 2, a->v, (size_t)(a->n + 1) * sizeof(char *));
	stray_provenance_set(a->n + 2, full);
	free(full);
	r->command = strdup(stray_provenance_command());
	cli.prog = "stray";
	cli.json = 1;
	opterr = 0;	/* as stray.c: our own one-line messages */
	optind = 0;	/* glibc: full re-initialisation for the command */
	cli_capture = &r->cap;
	rc = cli_run_command(c, a->n, a->v);
	cli_capture = NULL;
	cli.json = 0;
	return rc;
}

int stray_api_run(const char *cmd, const char *opts_json,
		  struct stray_api_result **out)
{
	struct stray_api_result *r = result_new();
	struct api_args a = { NULL, 0, 0 };
	const struct cmd *c;
	int rc;

	*out = r;
	if (!r)
		return CLI_FAIL;
	c = cmd ? cli_find_command(cmd) : NULL;
	if (!c) {
		snprintf(r->cap.err, sizeof(r->cap.err), "stray: '%s' is not "
			 "a stray command; see 'stray --help'",
			 cmd ? cmd : "");
		return CLI_USAGE;
	}
	rc = api_build_args(cmd, opts_json, &a, r->cap.err,
			    sizeof(r->cap.err));
	if (rc == CLI_FAIL)	/* building the argument list: memory */
		snprintf(r->cap.err, sizeof(r->cap.err),
			 "stray %s: out of memory", cmd);
	if (rc == CLI_OK) {
		pthread_mutex_lock(&api_lock);
		tracer_cancel_set(0);
		rc = run_locked(r, c, &a);
		pthread_mutex_unlock(&api_lock);
	}
	api_args_free(&a);
	/* a failure that said why on stderr only (a warning-style line) */
	if (rc != CLI_OK && !r->cap.err[0])
		snprintf(r->cap.err, sizeof(r->cap.err), "stray %s: failed "
			 "(exit %d; the reason is on standard error)", cmd, rc);
	if (r->cap.json) {
		r->json = cJSON_PrintUnformatted(r->cap.json);
		cJSON_Delete(r->cap.json);
		r->cap.json = NULL;
	}
	return rc;
}

const char *stray_api_json(const struct stray_api_result *r)
{
	return r ? r->json : NULL;
}

const char *stray_api_error(const struct stray_api_result *r)
{
	return r ? r->cap.err : "out of memory";
}

const char *stray_api_notes(const struct stray_api_result *r)
{
	return r ? r->cap.notes : "";
}

const char *stray_api_command(const struct stray_api_result *r)
{
	return r && r->command ? r->command : "";
}

size_t stray_api_curve_rows(const struct stray_api_result *r)
{
	return r && r->cap.has_curve ? r->cap.curve.n : 0;
}

size_t stray_api_curve_columns(const struct stray_api_result *r)
{
	const struct stray_curve *c = &r->cap.curve;

	if (!stray_api_curve_rows(r))
		return 0;
	return 2 + (c->sigma != NULL) + c->n_extra;
}

/* Column k: theta_deg, alpha, [sigma], extras. */
static int column(const struct stray_api_result *r, size_t k,
		  const char **name, const double **v)
{
	const struct stray_curve *c = &r->cap.curve;
	size_t s = c->sigma != NULL;

	if (k >= stray_api_curve_columns(r))
		return 1;
	if (k == 0) {
		*name = "theta_deg";
		*v = c->theta_deg;
	} else if (k == 1) {
		*name = "alpha";
		*v = c->alpha;
	} else if (k == 2 && s) {
		*name = "sigma";
		*v = c->sigma;
	} else {
		*name = c->extra_name[k - 2 - s];
		*v = c->extra[k - 2 - s];
	}
	return 0;
}

const char *stray_api_curve_name(const struct stray_api_result *r, size_t k)
{
	const char *name;
	const double *v;

	return column(r, k, &name, &v) ? NULL : name;
}

const double *stray_api_curve_column(const struct stray_api_result *r,
				     size_t k)
{
	const char *name;
	const double *v;

	return column(r, k, &name, &v) ? NULL : v;
}

size_t stray_api_curve_n_meta(const struct stray_api_result *r)
{
	return stray_api_curve_rows(r) ? r->cap.curve.n_meta : 0;
}

const char *stray_api_curve_meta(const struct stray_api_result *r, size_t i)
{
	return i < stray_api_curve_n_meta(r) ? r->cap.curve.meta[i] : NULL;
}

uint16_t *stray_api_frames_take(struct stray_api_result *r, size_t *n,
				int *rows, int *cols)
{
	uint16_t *f = r ? r->cap.frames : NULL;

	*n = f ? r->cap.n_frames : 0;
	*rows = f ? r->cap.rows : 0;
	*cols = f ? r->cap.cols : 0;
	if (f)
		r->cap.frames = NULL;
	return f;
}

void stray_api_free(void *p)
{
	free(p);
}

void stray_api_result_free(struct stray_api_result *r)
{
	if (!r)
		return;
	cli_capture_free(&r->cap);
	free(r->json);
	free(r->command);
	free(r);
}

/* err as the one line, without a command (no command ran). */
static int fail(struct stray_api_result *r, const struct stray_error *err)
{
	stray_error_format(err, r->cap.err, sizeof(r->cap.err));
	return stray_status_is_bad_input(err->code) ? CLI_USAGE : CLI_FAIL;
}

int stray_api_curve_read(const char *path, struct stray_api_result **out)
{
	struct stray_api_result *r = result_new();
	struct stray_error err;

	*out = r;
	if (!r)
		return CLI_FAIL;
	stray_error_clear(&err);
	if (stray_curve_load(path, &r->cap.curve, &err) != STRAY_OK)
		return fail(r, &err);
	r->cap.has_curve = 1;
	return CLI_OK;
}

int stray_api_curve_write(const char *path, const char *command, size_t n,
			  size_t n_cols, const char *const *names,
			  const double *const *cols, size_t n_meta,
			  const char *const *meta,
			  struct stray_api_result **out)
{
	struct stray_api_result *r = result_new();
	struct stray_curve c;
	struct stray_error err;
	size_t k, s;
	int rc;

	*out = r;
	if (!r)
		return CLI_FAIL;
	stray_error_clear(&err);
	if (n_cols < 2 || strcmp(names[0], "theta_deg") ||
	    strcmp(names[1], "alpha")) {
		stray_error_at(&err, STRAY_EINVAL, path, 0, "columns",
			       "the first two are theta_deg and alpha");
		return fail(r, &err);
	}
	s = n_cols > 2 && strcmp(names[2], "sigma") == 0;
	if ((rc = stray_curve_alloc(&c, n, (int)s, &err)) != STRAY_OK)
		return fail(r, &err);
	memcpy(c.theta_deg, cols[0], n * sizeof(double));
	memcpy(c.alpha, cols[1], n * sizeof(double));
	if (s)
		memcpy(c.sigma, cols[2], n * sizeof(double));
	for (k = 2 + s; k < n_cols && !rc; k++)
		rc = stray_curve_add_column(&c, names[k], cols[k], &err);
	/* the caller's comment lines as they were (the writer replaces
	 * "command:" and "version:" with this run's) */
	if (!rc && n_meta && !(c.meta = calloc(n_meta, sizeof(char *))))
		rc = stray_error_set(&err, STRAY_ENOMEM, "meta", NULL);
	for (k = 0; k < n_meta && !rc; k++) {
		if (!(c.meta[k] = strdup(meta[k])))
			rc = stray_error_set(&err, STRAY_ENOMEM, "meta", NULL);
		else
			c.n_meta = k + 1;
	}
	if (!rc) {
		pthread_mutex_lock(&api_lock);
		stray_provenance_set_text(command);
		rc = stray_curve_save(path, &c, &err);
		pthread_mutex_unlock(&api_lock);
	}
	stray_curve_free(&c);
	return rc ? fail(r, &err) : CLI_OK;
}

void stray_api_cancel(int on)
{
	tracer_cancel_set(on);
}

const char *stray_api_version(void)
{
	return stray_provenance_version();
}
