/*
 * api.h - the `stray` commands as one flat C call each (issue 32): what
 * Python (python/straylight, through ctypes) and any other language
 * binds to.  A call runs the command's own code in this process, as
 * `stray --json <cmd> ...` would (the same functions, the same numbers
 * for the same seed and threads, the same one-line error), and keeps
 * what the command would print or write for its caller: the --json
 * object, the error line, the curve it writes (trace, reduce) and the
 * frames it renders (frames).  Calls are serialised by a lock (the
 * commands share the process's option parser); a trace running in one
 * is stopped from another thread with stray_api_cancel.
 */
#ifndef STRAY_TOOLS_API_H
#define STRAY_TOOLS_API_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

struct stray_api_result;

/*
 * Run command cmd ("trace", "frames", ...) with options opts_json, a JSON
 * object: each key a long option of the command, given as `--key value`
 * (a string, or a number written %.17g); true: the flag `--key`; false
 * or null: left out; an array: the option once per element; the key
 * "args": an array of operands.  NULL or "" is no option.  Returns the
 * exit code of `stray` (0 ok, 1 failure, 2 bad input); *out (free it
 * with stray_api_result_free) is NULL only when memory ran out.
 */
int stray_api_run(const char *cmd, const char *opts_json,
		  struct stray_api_result **out);

/* The --json object as compact JSON text, or NULL when none. */
const char *stray_api_json(const struct stray_api_result *r);

/* The line `stray` prints on stderr when the call failed, or "". */
const char *stray_api_error(const struct stray_api_result *r);

/* The notes the command gave beside its result (what `stray` prints on
 * stderr and goes on: a scene put right, a body not excluded, a partial
 * sweep), one per line, each ending '\n'; "" when none. */
const char *stray_api_notes(const struct stray_api_result *r);

/* The command line the call is equivalent to (provenance). */
const char *stray_api_command(const struct stray_api_result *r);

/* The curve the command wrote (trace, reduce; the one read by
 * stray_api_curve_read): rows (0: none), columns (theta_deg, alpha,
 * then sigma when present, then the further named ones), and its
 * comment lines (without '#'). */
size_t stray_api_curve_rows(const struct stray_api_result *r);
size_t stray_api_curve_columns(const struct stray_api_result *r);
const char *stray_api_curve_name(const struct stray_api_result *r,
				 size_t k);
const double *stray_api_curve_column(const struct stray_api_result *r,
				     size_t k);
size_t stray_api_curve_n_meta(const struct stray_api_result *r);
const char *stray_api_curve_meta(const struct stray_api_result *r,
				 size_t i);

/*
 * The frames the command rendered, n x rows x cols counts in one buffer,
 * handed to the caller (free it with stray_api_free); NULL when none or
 * already taken.
 */
uint16_t *stray_api_frames_take(struct stray_api_result *r, size_t *n,
				int *rows, int *cols);
void stray_api_free(void *p);

void stray_api_result_free(struct stray_api_result *r);

/* Load a curve CSV (docs/formats.md) with the reader the commands use;
 * its rows through stray_api_curve_*.  0 or the exit code of bad input
 * (2) or another failure (1), the message in stray_api_error. */
int stray_api_curve_read(const char *path, struct stray_api_result **out);

/*
 * Write a curve CSV with the writer the commands use: n rows of n_cols
 * columns (names[0] = "theta_deg", names[1] = "alpha", then "sigma" or
 * further names), n_meta comment lines (without '#'; a "command:" or
 * "version:" line is replaced by command and this library's version).
 */
int stray_api_curve_write(const char *path, const char *command, size_t n,
			  size_t n_cols, const char *const *names,
			  const double *const *cols, size_t n_meta,
			  const char *const *meta,
			  struct stray_api_result **out);

/* Stop the trace running in a call (it then fails, "interrupted"), or
 * allow traces again (0: stray_api_run clears it at its start). */
void stray_api_cancel(int on);

/* What `stray --version` prints after "stray ". */
const char *stray_api_version(void);

#ifdef __cplusplus
}
#endif

#endif /* STRAY_TOOLS_API_H */
