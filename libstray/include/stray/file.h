/*
 * file.h - whole-file reads and atomic writes (hosted).
 *
 * Output files are written to a temporary sibling, flushed, fsynced and
 * renamed over the target, so a crash or a full disk never leaves a
 * half-written curve where a good one was.
 */
#ifndef STRAY_FILE_H
#define STRAY_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "stray/error.h"

/* Input limit (docs/limits.md): no input file is read past this size. */
#define STRAY_FILE_READ_MAX (256L * 1024 * 1024)

/*
 * Read a whole regular file into a new NUL-terminated buffer (caller
 * frees).  A directory, a device or a file over STRAY_FILE_READ_MAX is
 * refused as bad input (STRAY_EINVAL) before anything is read.
 */
int stray_file_read(const char *path, char **buf, size_t *len,
		    struct stray_error *err);

struct stray_file_out {
	FILE *f;
	char tmp[4096];
	const char *path;
};

/* Open a temporary sibling of path for writing. */
int stray_file_open_atomic(struct stray_file_out *out, const char *path,
			   struct stray_error *err);

/* Flush, fsync and rename into place; on any earlier write error, remove
 * the temporary and report. */
int stray_file_commit(struct stray_file_out *out, struct stray_error *err);

/* Abandon: close and remove the temporary. */
void stray_file_abort(struct stray_file_out *out);

/*
 * One run, all or nothing: after stray_file_defer, stray_file_commit
 * closes and syncs but leaves the temporary in place (the target path
 * is copied); stray_file_finish(1) then renames every one into
 * place, stray_file_finish(0) removes them all.  Temporaries are always
 * removed on exit, SIGINT, SIGTERM and SIGHUP unless committed.
 */
void stray_file_defer(void);
int stray_file_finish(int ok, struct stray_error *err);

/*
 * A folder written as one output (a sweep folder of `stray frames`):
 * filled as path.tmp.PID, renamed into place by stray_dir_commit (at
 * stray_file_finish when deferred), removed with its files on abort,
 * failure, exit and the signals above.  path must not exist or be an
 * empty folder (refused as bad input before anything is written).
 */
struct stray_dir_out {
	char tmp[4096];		/* the folder to fill */
	const char *path;
};

int stray_dir_open_atomic(struct stray_dir_out *out, const char *path,
			  struct stray_error *err);
int stray_dir_commit(struct stray_dir_out *out, struct stray_error *err);
void stray_dir_abort(struct stray_dir_out *out);

/*
 * One run's inputs and outputs (file_guard.c): after stray_file_run_begin,
 * an output that is a file this run has read (stray_file_read records
 * every file it reads; other readers - cfitsio, assimp - call
 * stray_file_note_input), or that another output of the run already
 * named, is refused by stray_file_open_atomic / stray_dir_open_atomic as
 * bad input (STRAY_EINVAL) before anything is written.  Without
 * stray_file_run_begin nothing is recorded or refused.
 */
void stray_file_run_begin(void);
void stray_file_run_end(void);
void stray_file_note_input(const char *path);
/* A file this run read and now replaces on purpose (a stale entry of a
 * resumable store): no longer an input. */
void stray_file_forget_input(const char *path);
/* An output this run rewrites on purpose (a progress record written again
 * after every step): it may be opened once more. */
void stray_file_forget_output(const char *path);
/* The refusal itself (also for writers outside stray_file_open_atomic);
 * records path as an output when accepted. */
int stray_file_claim_output(const char *path, struct stray_error *err);
/* path with its folder resolved (realpath of the parent + the name);
 * 0, or -1 when it does not fit in size. */
int stray_file_canonical(const char *path, char *out, size_t size);

#endif /* STRAY_FILE_H */
